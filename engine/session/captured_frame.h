// A capture reopened without its scene: the manifest's resources with their descriptions
// and decoders, each image's stored values as a read-back (exact integers for integer
// images), and the images on the GPU so the display pass can show them as it shows a live
// frame. What the editor's viewer needs, from files alone.
#pragma once

#include "graph/executor.h"
#include "session/session.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace tl::session {

class CapturedFrame {
 public:
  // Throws SessionError naming the folder when it holds no readable manifest.
  CapturedFrame(gpu::Device& device, const std::filesystem::path& dir);

  const std::filesystem::path& dir() const { return dir_; }
  const nlohmann::json& manifest() const { return manifest_; }
  // Images of the capture as the live graph described them (imported scene data left out).
  const std::vector<graph::PhysicalInfo>& resources() const { return resources_; }
  const std::vector<graph::PassTiming>& timings() const { return timings_; }
  uint32_t width() const { return width_; }
  // The scene as far as decoders need it without the scene: instance names.
  const scene::Scene& decodingScene() const { return names_; }
  uint32_t height() const { return height_; }

  // The stored values, loaded on first use. Throws SessionError for a name not captured.
  const graph::Readback& readback(const std::string& name);
  // Renders the display pass over one captured image into `executor`'s display.ldr.
  void display(graph::Executor& executor, lighting::DisplayPass& pass, const lighting::DisplayRequest& request);

 private:
  gpu::Image& image(const std::string& name);
  gpu::Device& device_;
  std::filesystem::path dir_;
  nlohmann::json manifest_;
  std::vector<graph::PhysicalInfo> resources_;
  std::vector<graph::PassTiming> timings_;
  struct Stored {
    std::string file, encoding, format;  // format: the original's name (gpu::FormatInfo::name)
    std::vector<std::string> channels;   // names in the frame's order (schema 2)
  };
  std::map<std::string, Stored> files_;
  float znear_ = 0.0f;  // the camera's near plane: view depth back to reversed Z
  std::map<std::string, graph::Readback> readbacks_;
  std::map<std::string, gpu::Image> images_;
  gpu::Image noInstances_;
  scene::Scene names_;  // a 1x1 zero gbuffer.instanceId when the capture has none
  uint32_t width_ = 0, height_ = 0;
};

}  // namespace tl::session
