// The Vulkan device: instance, physical-device choice, logical device and queue, a timeline
// of submissions, deferred destruction, validation-message accounting and debug names.
// Everything above engine/gpu talks to Vulkan through this and the other gpu/ headers.
#pragma once

#include "gpu/check.h"

#include <vulkan/vulkan_core.h>

#include <array>
#include <atomic>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <tuple>
#include <functional>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace tl::gpu {

struct DeviceOptions {
  bool validation = false;  // also switched on by TWINLIGHT_VALIDATION=1
  std::string preferredName;  // substring of the device name; TWINLIGHT_DEVICE overrides
  std::vector<std::string> instanceExtensions;  // e.g. what GLFW needs for a surface
  bool swapchain = false;                       // enable VK_KHR_swapchain on the device
  // The watchdog: work the device has not finished after this long stops the process with
  // one error line (exit status kExitDeviceHung); TWINLIGHT_GPU_TIMEOUT overrides it.
  double gpuTimeoutSeconds = 600.0;
};

// Exit status of a process the watchdog stopped.
inline constexpr int kExitDeviceHung = 4;

// Frames the host may have submitted before it waits for the oldest (see UploadRing).
inline constexpr uint32_t kMaxFramesInFlight = 2;

// A sampler by what it does; the device keeps one VkSampler per distinct description
// (Device::sampler), named after it, so passes share them instead of each making its own.
struct SamplerDesc {
  VkFilter filter = VK_FILTER_NEAREST;
  VkSamplerAddressMode address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  bool compareDepth = false;  // a depth comparison sampler (shadow maps)
  const char* name = "point.clamp";
  auto key() const { return std::tuple(int(filter), int(address), compareDepth); }
};

class PipelineCache;  // gpu/pipeline.h

// Extension entry points, loaded once.
struct Extensions {
  PFN_vkCmdPushDescriptorSetKHR cmdPushDescriptorSet = nullptr;
  PFN_vkSetDebugUtilsObjectNameEXT setObjectName = nullptr;
  PFN_vkCmdBeginDebugUtilsLabelEXT cmdBeginLabel = nullptr;
  PFN_vkCmdEndDebugUtilsLabelEXT cmdEndLabel = nullptr;
  PFN_vkCreateAccelerationStructureKHR createAccelerationStructure = nullptr;
  PFN_vkDestroyAccelerationStructureKHR destroyAccelerationStructure = nullptr;
  PFN_vkGetAccelerationStructureBuildSizesKHR getAccelerationStructureBuildSizes = nullptr;
  PFN_vkCmdBuildAccelerationStructuresKHR cmdBuildAccelerationStructures = nullptr;
  PFN_vkGetAccelerationStructureDeviceAddressKHR getAccelerationStructureDeviceAddress = nullptr;
  PFN_vkCmdWriteAccelerationStructuresPropertiesKHR cmdWriteAccelerationStructuresProperties = nullptr;
  PFN_vkCmdCopyAccelerationStructureKHR cmdCopyAccelerationStructure = nullptr;
  PFN_vkCreateRayTracingPipelinesKHR createRayTracingPipelines = nullptr;
  PFN_vkGetRayTracingShaderGroupHandlesKHR getRayTracingShaderGroupHandles = nullptr;
  PFN_vkCmdTraceRaysKHR cmdTraceRays = nullptr;
};

struct RayTracingSupport {
  bool pipeline = false;  // VK_KHR_ray_tracing_pipeline + acceleration structures
  bool query = false;     // VK_KHR_ray_query
  std::string unavailableReason;  // why `pipeline` is false, for the UI and the CLI
  VkPhysicalDeviceRayTracingPipelinePropertiesKHR pipelineProperties{};
};

class Device {
 public:
  explicit Device(const DeviceOptions& options = {});
  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physical() const { return physical_; }
  VkDevice handle() const { return device_; }
  VkQueue queue() const { return queue_; }
  uint32_t queueFamily() const { return queueFamily_; }
  const std::string& name() const { return name_; }
  const std::string& driver() const { return driver_; }
  uint32_t apiVersion() const { return apiVersion_; }
  const Extensions& ext() const { return ext_; }
  const RayTracingSupport& rayTracing() const { return rayTracing_; }
  const VkPhysicalDeviceLimits& limits() const { return limits_; }
  bool validationEnabled() const { return validation_; }
  // Many draws in one indirect call, each with its own first instance (the optional features
  // multiDrawIndirect and drawIndirectFirstInstance, enabled where present): gpu/draw_arena.h.
  bool multiDrawIndirect() const { return multiDrawIndirect_; }

  // Validation errors reported by the layers since creation (warnings are only logged).
  uint32_t validationErrorCount() const { return validationErrors_.load(); }
  std::vector<std::string> validationMessages() const;

  uint32_t findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required,
                          VkMemoryPropertyFlags preferred = 0) const;
  // Every allocation is counted against the device's stated limits before it is made: one
  // allocation at most maxMemoryAllocationSize, a heap's allocations at most its size. Over
  // either, Error with the figures (Vulkan leaves larger allocations undefined: lavapipe
  // crashed in a worker thread at 12000x12000). releaseMemory gives the bytes back.
  void reserveMemory(uint32_t memoryType, VkDeviceSize bytes, std::string_view name);
  void releaseMemory(uint32_t memoryType, VkDeviceSize bytes);
  VkDeviceSize maxAllocationSize() const { return maxAllocationSize_; }
  // Allocations made since the device was created: a steady frame makes none (tests).
  uint64_t allocationsMade() const { return allocationsMade_.load(); }

  // Submission timeline. Every submit signals the next value of one timeline semaphore.
  // At most kMaxFramesInFlight frames are submitted and not yet finished (graph::Executor):
  // the host records one while the GPU runs the one before.
  VkCommandBuffer beginCommands();
  uint64_t submit(VkCommandBuffer cmd, const std::vector<VkSemaphoreSubmitInfo>& waits = {},
                  const std::vector<VkSemaphoreSubmitInfo>& signals = {});
  void wait(uint64_t value);
  void waitIdle();
  uint64_t completedValue() const;
  uint64_t lastSubmittedValue() const { return submitted_; }
  // Records, submits and waits: for uploads and read-backs outside the frame.
  void immediate(const std::function<void(VkCommandBuffer)>& record);

  // Runs `destroy` once the GPU has finished every submission made so far (and the one
  // being recorded). RAII objects call this from their destructors.
  void destroyLater(std::function<void()> destroy);
  void collectGarbage();

  // A descriptor-set layout made once per distinct `key` (its bindings, counts and flags) and
  // kept until the device goes. Tables that come and go with a scene share it, so pipelines
  // built on it stay valid across scenes and need not be compiled again (on lavapipe a
  // ray-tracing pipeline takes tens of seconds to compile).
  // The device-wide sampler for `desc`: made on first use, destroyed with the device.
  VkSampler sampler(const SamplerDesc& desc);
  // The device-wide pipelines built by description (gpu/pipeline.h), destroyed with the device.
  PipelineCache& pipelines();
  VkDescriptorSetLayout sharedSetLayout(const std::string& key, const VkDescriptorSetLayoutCreateInfo& info);

  // VK_EXT_debug_utils names and labels; no-ops when the extension is absent.
  void setName(VkObjectType type, uint64_t handle, std::string_view name) const;
  void beginLabel(VkCommandBuffer cmd, std::string_view label) const;
  void endLabel(VkCommandBuffer cmd) const;

 private:
  void createInstance(const DeviceOptions& options);
  void choosePhysicalDevice(const DeviceOptions& options);
  void createLogicalDevice(const DeviceOptions& options);
  static VkBool32 VKAPI_PTR debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                          VkDebugUtilsMessageTypeFlagsEXT types,
                                          const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);

  struct CommandSlot {
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    uint64_t value = 0;  // timeline value of its last submission
    bool recording = false;
  };
  struct Garbage {
    uint64_t after;
    std::function<void()> destroy;
  };

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t queueFamily_ = 0;
  VkSemaphore timeline_ = VK_NULL_HANDLE;
  uint64_t submitted_ = 0;
  std::string name_;
  std::string driver_;
  uint32_t apiVersion_ = 0;
  bool validation_ = false;
  bool multiDrawIndirect_ = false;
  bool debugUtils_ = false;
  Extensions ext_;
  RayTracingSupport rayTracing_;
  VkPhysicalDeviceLimits limits_{};
  VkPhysicalDeviceMemoryProperties memory_{};
  VkDeviceSize maxAllocationSize_ = 0;
  std::array<std::atomic<VkDeviceSize>, VK_MAX_MEMORY_HEAPS> allocated_{};
  std::atomic<uint64_t> allocationsMade_{0};
  void waitTimeline(uint64_t value);  // bounded by the watchdog
  double timeoutSeconds_ = 600.0;
  std::deque<CommandSlot> commandSlots_;
  std::deque<Garbage> garbage_;
  std::map<std::string, VkDescriptorSetLayout> sharedSetLayouts_;
  std::map<std::tuple<int, int, bool>, VkSampler> samplers_;
  std::unique_ptr<PipelineCache> pipelines_;
  std::atomic<uint32_t> validationErrors_{0};
  mutable std::mutex messagesMutex_;
  std::vector<std::string> messages_;
};

}  // namespace tl::gpu
