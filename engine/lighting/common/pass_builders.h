// Pass builders: a compute pass stated once, binding by binding, over the named-resource graph.
// Each call names a set-0 binding (a constant of shaders/shared/) and the graph resource behind
// it; that one list yields the graph accesses (setup), the push-descriptor layout and the
// pipeline (a device-wide cache, checked against the shader's own bindings), the descriptor
// writes at execute time with the image layouts the graph chose for the usage, and the
// samplers (the device's cache, one per description). What is left to a pass is its push
// constants and its dispatch size:
//
//   ComputePass(in.device, "tonemap", "common/tonemap.comp")
//       .uniform(shared::kTonemapFrame, kFrameConstants)
//       .sampled(shared::kTonemapSource, kCompositeHdr)
//       .storageOut(shared::kTonemapOutput, kTonemapLdr, ldrDesc)
//       .push(push)
//       .dispatch(w, h)
//       .add(graph);
//
// Misuse (a binding declared twice, a binding the shader has and the list lacks or types
// differently) is one error naming the pass, the binding and both sides.
#pragma once

#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "gpu/spirv_reflect.h"
#include "graph/graph.h"
#include "lighting/common/frame_inputs.h"

#include <cstring>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tl::lighting {

// The samplers passes use, by what they do (shared by every pass through Device::sampler).
namespace samplers {
inline constexpr gpu::SamplerDesc point{VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, false, "point.clamp"};
inline constexpr gpu::SamplerDesc linear{VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, false, "linear.clamp"};
inline constexpr gpu::SamplerDesc linearRepeat{VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_REPEAT, false, "linear.repeat"};
inline constexpr gpu::SamplerDesc shadowCompare{VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, true, "shadow.compare"};
// Outside the map is lit (border white + compare): the sun's fit covers the view.
inline constexpr gpu::SamplerDesc sunShadowCompare{VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER, true,
                                                   "shadow.compare.border"};
}  // namespace samplers

// Thrown for a pass whose binding list is wrong; the message names the pass and both sides.
struct PassBuilderError : gpu::Error {
  using gpu::Error::Error;
};

class ComputePass {
 public:
  ComputePass(gpu::Device& device, std::string name, std::string shader);

  // Buffers: a uniform block (the frame constants), storage read, storage written.
  ComputePass& uniform(uint32_t binding, std::string_view buffer);
  ComputePass& bufferIn(uint32_t binding, std::string_view buffer);
  ComputePass& bufferOut(uint32_t binding, std::string_view buffer);
  // Images: sampled, storage read, storage written (an existing resource, or one this pass
  // creates with `create`), storage read and written in place.
  ComputePass& sampled(uint32_t binding, std::string_view image, const gpu::SamplerDesc& sampler = samplers::point);
  ComputePass& storageIn(uint32_t binding, std::string_view image);
  ComputePass& storageOut(uint32_t binding, std::string_view image);
  ComputePass& storageOut(uint32_t binding, std::string_view image, const graph::ResourceDesc& create);
  ComputePass& storageInOut(uint32_t binding, std::string_view image);
  // A sampled input that may be absent from this frame's graph (nobody wrote it): then there
  // is no access and no descriptor (the binding is partially bound, no stand-in resource);
  // present() says which, for the push constant that tells the shader.
  ComputePass& optionalSampled(uint32_t binding, std::string_view image, const graph::RenderGraph& graph,
                               const gpu::SamplerDesc& sampler = samplers::point);
  // Last frame's `name` (declared persistent here) sampled at `binding`. Whether it holds
  // anything is the history's decision from the frame key (T9, frame_key.h): historyValid().
  ComputePass& history(uint32_t binding, std::string_view name, const graph::ResourceDesc& desc, graph::RenderGraph& graph,
                       FrameInputs& in, HistoryKeeper& keeper, const HistoryPolicy& policy,
                       const gpu::SamplerDesc& sampler = samplers::linear);
  // The same where the pass knows whether the input exists (a path's optional output).
  ComputePass& optionalSampled(uint32_t binding, std::string_view image, bool present,
                               const gpu::SamplerDesc& sampler = samplers::point);
  // A storage image read and written in place that the pass may leave unbound (an accumulation
  // the frame does not keep): absent, no access and no descriptor, as for optionalSampled.
  ComputePass& optionalStorageInOut(uint32_t binding, std::string_view image, bool present);
  bool historyValid() const { return historyValid_; }
  bool present(uint32_t binding) const;

  // A top level traced by ray queries: its handle, and the graph structures it stands for
  // (read as acceleration structures: the top level and the bottom levels it refers to).
  ComputePass& accelerationStructure(uint32_t binding, VkAccelerationStructureKHR tlas,
                                     const std::vector<std::string>& structures);
  // Made outside the frame and never written in it (the rt path's blue noise, uploaded once;
  // the scene's instance data, written at load): bound as they are, with no graph access.
  ComputePass& constantSampled(uint32_t binding, const gpu::Image& image, VkImageLayout layout,
                               const gpu::SamplerDesc& sampler = samplers::point);
  ComputePass& constantBuffer(uint32_t binding, VkBuffer buffer);
  // A resource the pass reads or writes without a set-0 binding (e.g. through another set).
  ComputePass& reads(std::string_view name, graph::Usage usage);

  template <class T>
  ComputePass& push(const T& constants) {
    pushBytes_.resize(sizeof(T));
    std::memcpy(pushBytes_.data(), &constants, sizeof(T));
    return *this;
  }
  ComputePass& dispatch(uint32_t width, uint32_t height, uint32_t depth = 1, uint32_t localX = 8, uint32_t localY = 8,
                        uint32_t localZ = 1);
  // Instead of one dispatch: records with the pipeline bound and the descriptors pending.
  ComputePass& record(std::function<void(graph::PassContext&)> fn);

  // Checks the list, gets the pipeline and adds the pass. Throws PassBuilderError.
  graph::PassId add(graph::RenderGraph& graph);

  enum class Kind : uint8_t { Uniform, BufferIn, BufferOut, Sampled, StorageIn, StorageOut, StorageInOut, Tlas };
  struct Entry {
    uint32_t binding = 0;
    Kind kind = Kind::Sampled;
    std::string resource;
    std::optional<graph::ResourceDesc> create;
    gpu::SamplerDesc sampler{};
    VkAccelerationStructureKHR tlas = VK_NULL_HANDLE;
    bool optional = false, present = true;
    bool constant = false;  // outside the graph: `view` (with `layout`) or `buffer`
    VkImageView view = VK_NULL_HANDLE;
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkBuffer buffer = VK_NULL_HANDLE;
  };
  // The layout the list yields (what the pipeline is built with), for tests and the docs.
  std::vector<gpu::Binding> layout() const;
  // Checks the list against the shader's set-0 bindings (gpu/spirv_reflect.h); throws.
  void check(const std::vector<gpu::ReflectedBinding>& shader) const;

 private:
  ComputePass& entry(uint32_t binding, Kind kind, std::string_view resource);
  gpu::Device& device_;
  std::string name_, shader_;
  std::vector<Entry> entries_;
  std::vector<std::pair<std::string, graph::Usage>> extraReads_;
  std::vector<uint8_t> pushBytes_;
  uint32_t size_[6] = {1, 1, 1, 8, 8, 1};
  std::function<void(graph::PassContext&)> record_;
  bool historyValid_ = false;
};

}  // namespace tl::lighting
