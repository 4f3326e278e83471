// Captures: every resource of the last frame written to a folder, images in files that other
// tools read right (session/capture_encoding.h: linear EXR with conventional channel names,
// display images as PNG, integers exact, 3D images as their z slices stacked downwards),
// buffers as raw bytes, plus manifest.json (schema 2): each resource with its file, encoding
// and channels, the frame, camera, lighting path, every render setting, the instance id table,
// per-pass timings and the Twinlight version. A capture reads back without the scene
// (readCaptureImage, session/captured_frame.h).
#pragma once

#include "session/session.h"

#include <nlohmann/json.hpp>

#include <filesystem>

namespace tl::session {

// Renders `frames` frames of the session's current scene, path and view with every resource
// read back, and writes the capture into `dir`. Returns the manifest it wrote.
nlohmann::json captureFrame(Session& session, const std::filesystem::path& dir, uint32_t frames);
// Writes the capture of the last frame, which must have been rendered after
// Session::requestAllBuffers() (the editor does so inside its own frame loop).
nlohmann::json writeCapture(Session& session, const std::filesystem::path& dir);

// A captured image as it was stored: width x (height * depth) texels of `channels` floats
// (integer images hold their exact integer values).
struct CapturedImage {
  uint32_t width = 0, height = 0, channels = 0;
  std::vector<float> values;
  bool integer = false;
  std::vector<uint32_t> integers;  // integer images: the exact stored values
};
// `channels`: the names in the order wanted (the manifest's channelNames). EXR files keep
// their channels sorted by name, so a reader must ask by name; empty: the file's order.
CapturedImage readCaptureImage(const std::filesystem::path& file, const std::vector<std::string>& channels = {});

}  // namespace tl::session
