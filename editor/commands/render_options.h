// The options every subcommand that renders shares (scene, size, settings, view, light), and
// how they set up a Session: the one place a headless command's scene, path and settings are
// decided, in the order the user guide states (defaults, --settings FILE, the options given
// explicitly, then each --set).
#pragma once

#include "cli_args.h"
#include "setting_aliases.h"

#include "session/session.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tl::editor {

struct RenderOptions {
  std::string scene;
  std::string path = "direct";
  std::string size = "640x360";
  uint32_t frames = 1;
  std::vector<std::string> outputs;
  ViewArgs view;
  LightArgs light;
  std::string dumpGraph;
  std::optional<uint32_t> spp;
  std::optional<double> untilNoise;  // render: the reference until its relative standard error is at most this
  std::optional<uint32_t> bounces;
  std::optional<float> sunSizeDegrees;
  // The short forms of render settings (--materials, --hard-shadows, --rt-mesh-ratio, ...): their
  // option names and what they set come from setting_aliases.h.
  SettingAliasValues aliases;
  std::string albedoDb;
  bool allowOutsideFiles = false;
  std::string renderDoc;  // RenderDoc capture path template for one more frame
  double time = 0.0;
  std::optional<double> animateFps;
  // Settings: a file (a settings object, or any JSON Twinlight wrote that records them), then
  // NAME=VALUE assignments; explicit options win over the file.
  std::string settingsFile;
  std::vector<std::string> sets;
  CLI::Option* sizeOption = nullptr;
  bool settingsMayListVariants = false;  // compare: a JSON array is a list of configurations
};

// content/atrium.gltf where the data folders are (gpu/install_paths.h).
std::filesystem::path defaultScene();

// --size, --set, --settings, the setting aliases, the camera and every light option.
void addViewAndLightOptions(CLI::App& cmd, RenderOptions& o);

// Scene, path, size, settings, view and light from the options every headless subcommand
// shares. Settings in order: defaults, --settings FILE, then the options given explicitly, then
// each --set.
void prepareSession(session::Session& session, const RenderOptions& o);

// The options besides the scene that decide what a compare measures, as given: shards of one
// sweep must have been started with the same ones.
nlohmann::json renderOptionsJson(const RenderOptions& o);

// One more frame, captured by RenderDoc into `pathTemplate` (RenderDoc appends the frame).
void renderDocFrame(session::Session& session, const std::filesystem::path& pathTemplate);

}  // namespace tl::editor

namespace tl::editor {

// `render`'s work: render the frames and write the images (also the editor's headless fallback).
int runRender(const RenderOptions& o);

}  // namespace tl::editor
