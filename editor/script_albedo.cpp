// Script commands on the albedo database: open, bake, override the selected instance's albedo
// with undo and redo, save, and the overrides orphaned by a scene change.
#include "script_commands.h"

#include "editor_app.h"

#include <fmt/format.h>

#include <sstream>

namespace tl::editor {
namespace {

void albedoDb(EditorApp& app, ScriptState&, const std::string& arg) { app.openAlbedoDatabase(arg); }

void albedoImpact(EditorApp& app, ScriptState&, const std::string&) {
  app.session().captureAlbedoBaseline();
  app.pinPreview("albedo.impact");
}

void albedoBake(EditorApp& app, ScriptState& s, const std::string&) {
  app.startAlbedoBake(false);
  s.waitBake = true;
}

// The albedo combination of the selected instance (the edit commands need one).
uint32_t selectedCombination(EditorApp& app, const char* command) {
  if (!app.selected()) throw ScriptFailure(fmt::format("{} needs a selected instance", command));
  return app.session().albedo().combinationOf(*app.selected());
}

void albedoOverride(EditorApp& app, ScriptState&, const std::string& arg) {
  const uint32_t c = selectedCombination(app, "albedo-override");
  glm::vec3 rgb;
  if (std::sscanf(arg.c_str(), "%f %f %f", &rgb.r, &rgb.g, &rgb.b) != 3) throw ScriptFailure("albedo-override needs R G B");
  app.session().albedo().setOverride(c, rgb);
}

void albedoUndo(EditorApp& app, ScriptState&, const std::string&) {
  selectedCombination(app, "albedo-undo");
  if (!app.session().albedo().undo()) throw ScriptFailure("nothing to undo");
}

void albedoRedo(EditorApp& app, ScriptState&, const std::string&) {
  selectedCombination(app, "albedo-redo");
  if (!app.session().albedo().redo()) throw ScriptFailure("nothing to redo");
}

void albedoSave(EditorApp& app, ScriptState&, const std::string&) {
  selectedCombination(app, "albedo-save");
  app.session().albedo().save();
}

void expectAlbedoSource(EditorApp& app, ScriptState&, const std::string& arg) {
  const uint32_t c = selectedCombination(app, "expect-albedo-source");
  std::string got = albedo::sourceName(app.session().albedo().entries()[c].source);
  if (got != arg) throw ScriptFailure(fmt::format("expected albedo source `{}`, but it is `{}`", arg, got));
  fmt::print("script: albedo source is `{}`\n", got);
}

void expectOrphans(EditorApp& app, ScriptState&, const std::string& arg) {
  const auto& lib = app.session().albedo();
  if (std::to_string(lib.orphanCount()) != arg)
    throw ScriptFailure(fmt::format("expected {} orphaned override(s), but there are {}", arg, lib.orphanCount()));
  fmt::print("script: {} orphaned override(s)\n", lib.orphanCount());
  for (const auto& o : lib.orphans())
    if (!o.removed)
      fmt::print("script: orphan `{}` {:.3f} {:.3f} {:.3f}: {}\n", o.label, o.rgb.r, o.rgb.g, o.rgb.b, albedo::orphanReason(o));
}

// The orphan numbered `index` among those listed (not removed), as the Albedo panel shows them.
size_t listedOrphan(const albedo::AlbedoLibrary& lib, size_t index) {
  for (size_t i = 0, listed = 0; i < lib.orphans().size(); ++i)
    if (!lib.orphans()[i].removed && listed++ == index) return i;
  throw ScriptFailure(fmt::format("there is no orphaned override {} ({} listed)", index, lib.orphanCount()));
}

// orphan-reapply I [selected]: to the orphan's new key (a combination with its name), or the selection's.
void orphanReapply(EditorApp& app, ScriptState&, const std::string& arg) {
  auto& lib = app.session().albedo();
  std::istringstream words(arg);
  size_t index = 0;
  std::string target;
  if (!(words >> index)) throw ScriptFailure("orphan-reapply needs the orphan's number (0 = the first listed)");
  words >> target;
  const size_t orphan = listedOrphan(lib, index);
  if (target == "selected") {
    if (!app.selected()) throw ScriptFailure("orphan-reapply N selected needs a selected instance");
    lib.reapplyOrphan(orphan, lib.combinationOf(*app.selected()));
  } else if (target.empty()) {
    const auto same = lib.orphans()[orphan].sameLabel;
    if (!same) throw ScriptFailure(fmt::format("`{}` has no new key (no combination with its name)", lib.orphans()[orphan].label));
    lib.reapplyOrphan(orphan, *same);
  } else {
    throw ScriptFailure(fmt::format("orphan-reapply N [selected], not `{}`", target));
  }
}

void orphanDelete(EditorApp& app, ScriptState&, const std::string& arg) {
  auto& lib = app.session().albedo();
  std::istringstream words(arg);
  size_t index = 0;
  if (!(words >> index)) throw ScriptFailure("orphan-delete needs the orphan's number (0 = the first listed)");
  lib.deleteOrphan(listedOrphan(lib, index));
}

constexpr ScriptCommand kCommands[] = {
    {"albedo-db", albedoDb},
    {"albedo-impact", albedoImpact},
    {"albedo-bake", albedoBake},
    {"albedo-override", albedoOverride},
    {"albedo-undo", albedoUndo},
    {"albedo-redo", albedoRedo},
    {"albedo-save", albedoSave},
    {"expect-albedo-source", expectAlbedoSource},
    {"expect-orphans", expectOrphans},
    {"orphan-reapply", orphanReapply},
    {"orphan-delete", orphanDelete},
};

}  // namespace

std::span<const ScriptCommand> albedoScriptCommands() { return kCommands; }

}  // namespace tl::editor
