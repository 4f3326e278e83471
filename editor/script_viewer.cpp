// Script commands on the buffer viewer: what the viewport shows, the channel, meaning, zoom,
// slice and probe, A/B copies, and captures reopened or compared with the viewer's read-back.
#include "script_commands.h"

#include "editor_app.h"
#include "gpu/formats.h"
#include "session/capture.h"
#include "session/capture_encoding.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace tl::editor {
namespace {

// The decoder of the resource on view ("" when it has none or is not a resource of the frame).
std::string viewedDecoder(EditorApp& app) {
  std::string decoder;
  for (const auto& r : app.session().resources())
    if (r.name == app.viewer().resource) decoder = r.desc.decoder;
  return decoder;
}

const graph::PhysicalInfo& viewedResource(EditorApp& app) {
  for (const auto& r : app.session().resources())
    if (r.name == app.viewer().resource) return r;
  throw ScriptFailure(fmt::format("`{}` is not a resource of the frame", app.viewer().resource));
}

void preview(EditorApp& app, ScriptState&, const std::string& arg) { app.pinPreview(arg == "final" ? "" : arg); }

void view(EditorApp& app, ScriptState&, const std::string& arg) {
  app.pinPreview(arg == "final" ? "" : arg);
  app.viewer().refresh = true;
}

void expectViewing(EditorApp& app, ScriptState&, const std::string& arg) {
  const std::string shown = app.pinnedPreview().empty() ? "final" : app.pinnedPreview();
  if (shown != arg) throw ScriptFailure(fmt::format("the viewport shows `{}`, not `{}`", shown, arg));
  fmt::print("script: the viewport shows `{}`\n", shown);
}

void viewChannel(EditorApp& app, ScriptState&, const std::string& arg) {
  static const char* names[] = {"rgb", "r", "g", "b", "a", "luminance"};
  auto it = std::find(std::begin(names), std::end(names), arg);
  if (it == std::end(names)) throw ScriptFailure(fmt::format("unknown channel `{}`", arg));
  app.viewer().channel = uint32_t(it - std::begin(names));
  app.viewer().autoFitPending = true;
}

void viewMeaning(EditorApp& app, ScriptState&, const std::string& arg) {
  if (arg != "on" && arg != "off") throw ScriptFailure("view-meaning on|off");
  app.viewer().meaning = arg == "on";
  app.viewer().autoFitPending = true;
}

void expectMeaning(EditorApp& app, ScriptState&, const std::string& arg) {
  const auto m = shownMeaning(app.viewer(), viewedDecoder(app));
  const std::string shown = m ? m->quantity : "stored values";
  if (shown.find(arg) == std::string::npos)
    throw ScriptFailure(fmt::format("expected `{}` to show {}, but it shows {}", app.viewer().resource, arg, shown));
  if (m && m->fitted && app.viewer().autoFitPending)
    throw ScriptFailure(fmt::format("`{}`: the {} range is not fitted yet", app.viewer().resource, shown));
  fmt::print("script: `{}` shows {}{}\n", app.viewer().resource, shown,
             m && m->fitted ? fmt::format(" over {:.4g} .. {:.4g} {}", app.viewer().rangeMin, app.viewer().rangeMax, m->unit)
                            : std::string());
}

void viewFalseColour(EditorApp& app, ScriptState&, const std::string& arg) { app.viewer().falseColour = arg == "on"; }

void viewZoom(EditorApp& app, ScriptState&, const std::string& arg) {
  float z, u, v;
  if (std::sscanf(arg.c_str(), "%f %f %f", &z, &u, &v) != 3) throw ScriptFailure("view-zoom needs Z U V");
  app.viewer().zoom = z, app.viewer().centre = glm::vec2(u, v);
}

void viewSlice(EditorApp& app, ScriptState&, const std::string& arg) { app.viewer().slice = uint32_t(std::stoul(arg)); }

void expectSlice(EditorApp& app, ScriptState&, const std::string& arg) {
  const graph::PhysicalInfo& info = viewedResource(app);
  const VkExtent3D e = info.desc.extent;
  const std::string shown = lighting::sliceMeaning(info.desc.decoder, e, app.viewer().slice);
  if (e.depth <= 1 || shown != arg)
    throw ScriptFailure(fmt::format("expected `{}`'s slice to read `{}`, but it reads `{}`", info.name, arg,
                                    e.depth > 1 ? shown : "nothing: it is 2D"));
  fmt::print("script: `{}` slice {}: {}\n", info.name, app.viewer().slice, shown);
}

// A texel's width and height on screen, from the window the viewer shows.
void expectSquareTexels(EditorApp& app, ScriptState&, const std::string&) {
  const graph::PhysicalInfo& info = viewedResource(app);
  const VkExtent3D e = info.desc.extent;
  const glm::vec4 w = viewerWindow(app.viewer());
  const glm::vec2 viewport = app.viewportSize();
  const float texelW = viewport.x / (w.z * float(e.width)), texelH = viewport.y / (w.w * float(e.height));
  if (!(std::abs(texelW / texelH - 1.0f) < 0.01f))
    throw ScriptFailure(fmt::format("`{}` ({}x{}) shows texels {:.3f} x {:.3f} px: not square", info.name, e.width,
                                    e.height, texelW, texelH));
  fmt::print("script: `{}` ({}x{}) shows square texels of {:.3f} px, window {:.3f} x {:.3f} of the image\n", info.name,
             e.width, e.height, texelW, w.z, w.w);
}

void viewProbe(EditorApp& app, ScriptState&, const std::string& arg) {
  unsigned x, y;
  if (std::sscanf(arg.c_str(), "%u %u", &x, &y) != 2) throw ScriptFailure("view-probe needs X Y");
  app.viewer().probe = glm::uvec3(x, y, app.viewer().slice);
}

void keepB(EditorApp& app, ScriptState&, const std::string&) { app.viewer().keepCopy = true; }
void showB(EditorApp& app, ScriptState&, const std::string& arg) { app.viewer().showCopy = arg == "on"; }

void expectProbe(EditorApp& app, ScriptState&, const std::string& arg) {
  unsigned x, y;
  char text[256] = {};
  if (std::sscanf(arg.c_str(), "%u %u %255[^\n]", &x, &y, text) != 3) throw ScriptFailure("expect-probe needs X Y TEXT");
  const ViewerState& v = app.viewer();
  // A volume is probed in the slice on view, as the viewport's own probe does.
  const auto lines = probeTexel(v, viewedDecoder(app), glm::uvec3(x, y, v.slice), app.session().decodingScene());
  if (!lines) throw ScriptFailure(fmt::format("`{}` was not read back", v.resource));
  std::string all;
  for (auto& [l, val] : lines->raw) all += l + " = " + val + "; ";
  for (auto& [l, val] : lines->decoded) all += l + ": " + val + "; ";
  bool found = false;  // TEXT may list alternatives: a|b
  std::istringstream alternatives{std::string(text)};
  for (std::string alt; std::getline(alternatives, alt, '|');) found |= !alt.empty() && all.find(alt) != std::string::npos;
  if (!found) throw ScriptFailure(fmt::format("probe of `{}` at {}, {} shows `{}`, not `{}`", v.resource, x, y, all, text));
  fmt::print("script: probe of `{}` at {}, {}: {}\n", v.resource, x, y, all);
}

void expectViewerMatchesCapture(EditorApp& app, ScriptState&, const std::string& arg) {
  const ViewerState& v = app.viewer();
  auto it = v.readbacks.find(v.resource);
  if (it == v.readbacks.end()) throw ScriptFailure(fmt::format("`{}` was not read back", v.resource));
  // The capture's file as its manifest describes it, decoded back to the frame's texels.
  const nlohmann::json manifest = nlohmann::json::parse(std::ifstream(std::filesystem::path(arg) / "manifest.json"));
  nlohmann::json entry;
  for (const auto& r : manifest["resources"])
    if (r.value("name", "") == v.resource) entry = r;
  if (!entry.is_object() || !entry["file"].is_string()) throw ScriptFailure(fmt::format("`{}` is not in the capture", v.resource));
  session::CapturedImage img = session::readCaptureImage(std::filesystem::path(arg) / entry["file"].get<std::string>(),
                                                         entry.value("channelNames", std::vector<std::string>{}));
  const std::vector<float> mine = it->second.texels();
  const std::vector<float> theirs =
      img.integer ? img.values
                  : session::decodeCaptureValues(entry.value("encoding", "linear"), entry.value("format", ""), img.values,
                                                 img.channels, gpu::formatInfo(it->second.format).channels,
                                                 manifest["camera"].value("znear", 0.0f));
  if (theirs.size() != mine.size())
    throw ScriptFailure(fmt::format("{} values in the viewer, {} in the capture", mine.size(), theirs.size()));
  size_t differ = 0;
  for (size_t i = 0; i < mine.size(); ++i) differ += !(mine[i] == theirs[i] || (std::isnan(mine[i]) && std::isnan(theirs[i])));
  if (differ) throw ScriptFailure(fmt::format("{} of {} values differ between the viewer and the capture", differ, mine.size()));
  fmt::print("script: the viewer's `{}` equals the capture ({} values)\n", v.resource, mine.size());
}

void openCapture(EditorApp& app, ScriptState&, const std::string& arg) {
  app.session().openCapture(arg);
  app.showBuffers(true);
  app.pinPreview("");
}

void closeCapture(EditorApp& app, ScriptState&, const std::string&) { app.session().closeCapture(); }

constexpr ScriptCommand kCommands[] = {
    {"preview", preview},
    {"view", view},
    {"expect-viewing", expectViewing},
    {"view-channel", viewChannel},
    {"view-meaning", viewMeaning},
    {"expect-meaning", expectMeaning},
    {"view-false-colour", viewFalseColour},
    {"view-zoom", viewZoom},
    {"view-slice", viewSlice},
    {"expect-slice", expectSlice},
    {"expect-square-texels", expectSquareTexels},
    {"view-probe", viewProbe},
    {"keep-b", keepB},
    {"show-b", showB},
    {"expect-probe", expectProbe},
    {"expect-viewer-matches-capture", expectViewerMatchesCapture},
    {"open-capture", openCapture},
    {"close-capture", closeCapture},
};

}  // namespace

std::span<const ScriptCommand> viewerScriptCommands() { return kCommands; }

}  // namespace tl::editor
