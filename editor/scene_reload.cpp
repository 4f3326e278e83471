// Reloading the scene when its file changes on disk: an artist re-exports from their tool and
// sees the result in place, from the same camera, with the same instance selected and the
// albedo overrides they were trying still applied.
#include "editor_app.h"

#include "session/image_io.h"

#include <GLFW/glfw3.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

namespace tl::editor {
void EditorApp::watchScene() {
  std::vector<std::filesystem::path> files;
  if (session_->hasScene()) {
    const scene::Scene& s = session_->scene();
    files.push_back(s.path);
    // A .gltf's buffer is usually the .bin of the same name; textures are listed.
    std::filesystem::path bin = s.path;
    bin.replace_extension(".bin");
    std::error_code ec;
    if (s.path.extension() != ".bin" && std::filesystem::exists(bin, ec)) files.push_back(bin);
    for (const auto& t : s.textures)
      if (!t.path.empty()) files.push_back(t.path);
  }
  sceneWatcher_.watch(std::move(files), glfwGetTime());
}

void EditorApp::reloadScene() {
  if (load_.valid() || !session_->hasScene()) return;
  const scene::Scene& s = session_->scene();
  KeptAcrossReload kept;
  if (selected_ && *selected_ < s.instances.size()) kept.selected = s.instances[*selected_].name;
  kept.overrides = unsavedOverrides();
  // The lighting the scene opened with is read again with it (the file, its sidecar); an edit
  // away from it is the artist's, and kept.
  const session::Lighting& now = session_->lighting();
  if (!session::sameLighting(now, savedLighting_)) kept.lighting = now;
  kept.animationTime = session_->animationTime();
  keptAcrossReload_ = std::move(kept);
  spdlog::info("{} changed on disk: reloading", s.path.string());
  // Opened as it was opened (a --lighting file given for it applies again); no question: the
  // artist's work is kept across the reload.
  beginOpen(openedWith_);
}

void EditorApp::restoreAfterReload() {
  KeptAcrossReload kept = std::move(*keptAcrossReload_);
  keptAcrossReload_.reset();
  const scene::Scene& s = session_->scene();
  selected_.reset();
  for (uint32_t i = 0; i < s.instances.size(); ++i)
    if (!kept.selected.empty() && s.instances[i].name == kept.selected) selected_ = i;
  // Overrides follow their mesh + material key: a combination the export changed is new,
  // and an override of the old one becomes an orphan (Albedo panel), never silently lost.
  // An unsaved clear of an override stays cleared (the database's override came back with the
  // reload: an undone override reappeared, found by the editor soak walk).
  auto& albedo = session_->albedo();
  const size_t orphansBefore = albedo.orphanCount();
  applyOverrides(kept.overrides);
  if (kept.lighting) session_->setLighting(*kept.lighting);
  session_->setAnimationTime(kept.animationTime);
  ++sceneReloads_;
  const std::string text = fmt::format("reloaded {} (changed on disk): camera, selection and overrides kept", s.path.string());
  fmt::print("{}\n", text);
  notify(text);
  if (albedo.orphanCount() > orphansBefore) notifyOrphans();
}

std::filesystem::path EditorApp::defaultImagePath(const char* extension) const {
  const std::string scene = session_->hasScene() ? session_->scene().name : "capture";
  return std::filesystem::path("renders") /
         fmt::format("{}-{}-frame{}{}", scene, session_->path(), session_->frameIndex(), extension);
}

void EditorApp::saveImage(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  for (auto& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".png" && ext != ".exr")
    throw session::SessionError(fmt::format("{}: unsupported image type `{}` (use .exr or .png)", file.string(), ext));
  session_->saveImage(file);  // the last frame's final images are always read back
  const std::string text = fmt::format("wrote {}", std::filesystem::absolute(file).string());
  fmt::print("{}\n", text);
  notify(text);
}

}  // namespace tl::editor
