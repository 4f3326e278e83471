// Script commands on the Compare panel: split the viewport between two paths, its mode and
// wipe, and the live reference's errors and restarts.
#include "script_commands.h"

#include "editor_app.h"

#include <fmt/format.h>

#include <cmath>
#include <sstream>

namespace tl::editor {
namespace {

void compare(EditorApp& app, ScriptState&, const std::string& arg) {
  std::istringstream sides(arg);
  std::string left, right;
  sides >> left >> right;
  if (left == "off") {
    app.setCompare(false);
    return;
  }
  if (right.empty()) throw ScriptFailure("compare needs LEFT RIGHT (or off)");
  app.setCompare(true);
  app.compareView()->left = left, app.compareView()->right = right;
  app.session().setCompareView(app.compareView());  // an unknown side fails here, on its line
}

session::CompareView& splitView(EditorApp& app) {
  if (!app.compareView()) throw ScriptFailure("the viewport is not split (compare LEFT RIGHT first)");
  return *app.compareView();
}

void compareMode(EditorApp& app, ScriptState&, const std::string& arg) { splitView(app).difference = arg == "difference"; }
void compareWipe(EditorApp& app, ScriptState&, const std::string& arg) { splitView(app).wipe = std::stof(arg); }

void expectCompareMode(EditorApp& app, ScriptState&, const std::string& arg) {
  if (!app.compareView()) throw ScriptFailure("the viewport is not split");
  const std::string mode = app.compareView()->difference ? "difference" : "wipe";
  if (mode != arg) throw ScriptFailure(fmt::format("the compare view shows `{}`, not `{}`", mode, arg));
  fmt::print("script: the compare view shows `{}`\n", mode);
}

void expectCompareErrors(EditorApp& app, ScriptState&, const std::string&) {
  session::LiveCompare* live = app.session().liveCompare();
  if (!live) throw ScriptFailure("the viewport is not split");
  live->finishFlip();  // FLIP runs beside the frames: take the one under way
  std::string all;
  for (const auto& e : live->errors()) {
    if (e.path == app.session().referencePath()) continue;
    if (!e.relMse || !std::isfinite(*e.relMse) || !e.flip || !std::isfinite(*e.flip))
      throw ScriptFailure(fmt::format("no finite error for `{}` yet", e.path));
    all += fmt::format(" {} relMSE {:.4f} FLIP {:.4f} ({:.1f} ms);", e.path, *e.relMse, *e.flip, e.gpuMs);
  }
  const auto noise = live->referenceNoise();
  fmt::print("script: compare against the reference ({} spp, its noise relMSE {}, {}):{}\n", live->referenceSamples(),
             noise ? fmt::format("{:.4f}", *noise) : std::string("not known yet"),
             live->referenceTrusted() ? "ranks the paths" : "still converging", all);
}

void expectReferenceRestarted(EditorApp& app, ScriptState& s, const std::string& arg) {
  const session::LiveCompare* live = app.session().liveCompare();
  if (!live) throw ScriptFailure("the viewport is not split");
  const std::string causes = lighting::describeParts(live->lastReferenceRestart());
  if (live->referenceRestarts() == s.restartsAtMove)
    throw ScriptFailure(fmt::format("the reference did not restart: {} samples per pixel, {} before the move",
                                    live->referenceSamples(), s.samplesAtMove));
  if ((", " + causes + ",").find(", " + arg + ",") == std::string::npos)
    throw ScriptFailure(fmt::format("the reference restarted for {}, not {}", causes, arg));
  if (live->referenceSamples() >= s.samplesAtMove)
    throw ScriptFailure(fmt::format("the reference holds {} samples per pixel, not fewer than the {} before the move",
                                    live->referenceSamples(), s.samplesAtMove));
  fmt::print("script: the reference restarted ({}): {} -> {} samples per pixel\n", causes, s.samplesAtMove,
             live->referenceSamples());
}

constexpr ScriptCommand kCommands[] = {
    {"compare", compare},
    {"compare-mode", compareMode},
    {"compare-wipe", compareWipe},
    {"expect-compare-mode", expectCompareMode},
    {"expect-compare-errors", expectCompareErrors},
    {"expect-reference-restarted", expectReferenceRestarted},
};

}  // namespace

std::span<const ScriptCommand> compareScriptCommands() { return kCommands; }

}  // namespace tl::editor
