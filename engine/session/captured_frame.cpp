#include "session/captured_frame.h"

#include "gpu/formats.h"
#include "lighting/common/gbuffer_pass.h"
#include "session/capture.h"
#include "session/capture_encoding.h"

#include <fmt/format.h>

#include <cstring>
#include <fstream>

namespace tl::session {
namespace {

// The format a captured image comes back in: 32-bit floats, or exact 32-bit integers, with
// the captured channel count (3 channels padded to 4: RGB32 is not a sampled format).
VkFormat capturedFormat(uint32_t channels, bool integer) {
  if (integer) return channels == 1 ? VK_FORMAT_R32_UINT : channels == 2 ? VK_FORMAT_R32G32_UINT : VK_FORMAT_R32G32B32A32_UINT;
  return channels == 1 ? VK_FORMAT_R32_SFLOAT : channels == 2 ? VK_FORMAT_R32G32_SFLOAT : VK_FORMAT_R32G32B32A32_SFLOAT;
}

}  // namespace

CapturedFrame::CapturedFrame(gpu::Device& device, const std::filesystem::path& dir) : device_(device), dir_(dir) {
  std::ifstream in(dir / "manifest.json");
  if (!in) throw SessionError(fmt::format("{}: no manifest.json (not a Twinlight capture)", dir.string()));
  try {
    manifest_ = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw SessionError(fmt::format("{}: manifest.json is not JSON: {}", dir.string(), e.what()));
  }
  if (!manifest_.contains("resources") || !manifest_["resources"].is_array())
    throw SessionError(fmt::format("{}: manifest.json lists no resources", dir.string()));
  for (const auto& n : manifest_.value("instances", nlohmann::json::array())) {
    names_.instances.emplace_back();
    names_.instances.back().name = n.is_string() ? n.get<std::string>() : "?";
  }
  znear_ = manifest_.value("/camera/znear"_json_pointer, View{}.znear);
  width_ = manifest_.value("/settings/width"_json_pointer, 0u);
  height_ = manifest_.value("/settings/height"_json_pointer, 0u);
  for (const auto& t : manifest_.value("timings", nlohmann::json::array())) timings_.push_back({t.value("pass", ""), t.value("gpuMs", 0.0)});
  for (const auto& r : manifest_["resources"]) {
    if (!r.contains("width") || !r["file"].is_string()) continue;  // buffers and what was not read back
    graph::PhysicalInfo info;
    info.name = r.value("name", "");
    info.writer = r.value("writer", "");
    info.persistent = r.value("persistent", false);
    info.aliased = r.value("aliased", false);
    const int64_t first = r.value("firstUse", int64_t(-1)), last = r.value("lastUse", int64_t(-1));
    info.firstUse = first < 0 ? graph::kNone : uint32_t(first);
    info.lastUse = last < 0 ? graph::kNone : uint32_t(last);
    info.bytes = r.value("memoryBytes", VkDeviceSize(0));
    const std::string format = r.value("format", "?");
    const bool integer = format.find("UI") != std::string::npos;  // every unsigned-integer format's name: R32UI, RG32UI, ...
    info.desc = graph::ResourceDesc::image3D(capturedFormat(r.value("channels", 4u), integer), r.value("width", 1u),
                                             r.value("height", 1u), std::max(1u, r.value("depth", 1u)),
                                             fmt::format("{} (captured from {})", r.value("description", ""), format));
    info.desc.decoder = r.value("decoder", "");
    // Schema 1 captures (no "encoding") stored every value raw.
    files_[info.name] = {r["file"].get<std::string>(), r.value("encoding", integer ? "uint" : "linear"), format,
                         r.value("channelNames", std::vector<std::string>{})};
    resources_.push_back(std::move(info));
  }
  if (resources_.empty()) throw SessionError(fmt::format("{}: the capture holds no images", dir.string()));
  if (width_ == 0 || height_ == 0) width_ = resources_.front().desc.extent.width, height_ = resources_.front().desc.extent.height;
}

const graph::Readback& CapturedFrame::readback(const std::string& name) {
  if (auto it = readbacks_.find(name); it != readbacks_.end()) return it->second;
  auto info = std::find_if(resources_.begin(), resources_.end(), [&](auto& r) { return r.name == name; });
  if (info == resources_.end()) throw SessionError(fmt::format("`{}` is not an image of capture {}", name, dir_.string()));
  const Stored& stored = files_.at(name);
  CapturedImage img = readCaptureImage(dir_ / stored.file, stored.channels);
  graph::Readback r;
  r.name = name;
  r.format = info->desc.format;
  r.extent = info->desc.extent;
  const uint32_t storedChannels = std::max(1u, img.channels), channels = gpu::formatInfo(r.format).channels;
  const size_t texels = size_t(img.width) * img.height;
  r.bytes.resize(texels * channels * 4, 0);
  if (img.integer) {
    for (size_t t = 0; t < texels; ++t)
      for (uint32_t c = 0; c < channels; ++c) {
        const uint32_t v = c < storedChannels ? img.integers[t * storedChannels + c] : 0u;
        std::memcpy(r.bytes.data() + (t * channels + c) * 4, &v, 4);
      }
  } else {
    const std::vector<float> values =
        decodeCaptureValues(stored.encoding, stored.format, img.values, storedChannels, channels, znear_);
    std::memcpy(r.bytes.data(), values.data(), std::min(r.bytes.size(), values.size() * 4));
  }
  return readbacks_[name] = std::move(r);
}

gpu::Image& CapturedFrame::image(const std::string& name) {
  if (auto it = images_.find(name); it != images_.end()) return it->second;
  const graph::Readback& r = readback(name);
  gpu::Image img(device_, {r.format, r.extent, 1, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT},
                 "capture." + name);
  gpu::uploadImage2D(device_, img, r.bytes.data(), r.bytes.size());
  return images_[name] = std::move(img);
}

void CapturedFrame::display(graph::Executor& executor, lighting::DisplayPass& pass, const lighting::DisplayRequest& request) {
  const std::string shown = request.source.empty() ? std::string("tonemap.ldr") : request.source;
  const std::string ids(lighting::gbuffer::kInstanceId);
  graph::RenderGraph graph;
  std::vector<std::string> names{shown};
  if (shown != ids) names.push_back(ids);
  for (const std::string& name : names) {
    auto info = std::find_if(resources_.begin(), resources_.end(), [&](auto& r) { return r.name == name; });
    if (info != resources_.end()) {
      graph.declareImported(name, info->desc);
      executor.bindImportedImage(name, image(name), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    } else if (name == ids) {
      if (!noInstances_) {
        noInstances_ = gpu::Image(device_, {VK_FORMAT_R32_UINT, {1, 1, 1}, 1, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT},
                                  "capture.noInstances");
        const uint32_t zero = 0;
        gpu::uploadImage2D(device_, noInstances_, &zero, 4);
      }
      graph.declareImported(ids, graph::ResourceDesc::image2D(VK_FORMAT_R32_UINT, 1, 1, "no instance ids in this capture"));
      executor.bindImportedImage(ids, noInstances_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    } else {
      throw SessionError(fmt::format("`{}` is not an image of capture {}", name, dir_.string()));
    }
  }
  lighting::DisplayRequest r = request;
  r.source = shown;
  r.keepCopy = false;  // A/B works on live frames
  r.showCopy = false;
  pass.add(graph, device_, width_, height_, r);
  executor.execute(graph, graph.compile(executor.entryStates(graph)));
}

}  // namespace tl::session
