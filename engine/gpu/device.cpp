#include "gpu/device.h"
#include "gpu/keep_libraries_loaded.h"
#include "gpu/pipeline.h"
#include "gpu/renderdoc.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>

namespace tl::gpu {
namespace {

bool envFlag(const char* name) {
  const char* v = std::getenv(name);
  return v && *v && std::string_view(v) != "0";
}

// The watchdog's limit: seconds the device may take to finish work it was given.
double watchdogSeconds(const DeviceOptions& options) {
  if (const char* v = std::getenv("TWINLIGHT_GPU_TIMEOUT"); v && *v) {
    char* end = nullptr;
    const double s = std::strtod(v, &end);
    if (end && *end == '\0' && s > 0.0 && s <= 1e6) return s;
    spdlog::warn("TWINLIGHT_GPU_TIMEOUT=`{}` is not a number of seconds from 0 to 1e6; using {} s", v,
                 options.gpuTimeoutSeconds);
  }
  return options.gpuTimeoutSeconds;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::set<std::string> deviceExtensions(VkPhysicalDevice pd) {
  uint32_t n = 0;
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> props(n);
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, props.data());
  std::set<std::string> out;
  for (auto& p : props) out.insert(p.extensionName);
  return out;
}

// Ray tracing needs all three extensions and their features; the reason it is missing is
// shown to the user verbatim, so it names what is absent.
std::string rayTracingMissing(VkPhysicalDevice pd) {
  auto exts = deviceExtensions(pd);
  for (const char* e : {VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME, VK_KHR_RAY_TRACING_PIPELINE_EXTENSION_NAME,
                        VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME}) {
    if (!exts.count(e)) return fmt::format("the device does not support {}", e);
  }
  VkPhysicalDeviceAccelerationStructureFeaturesKHR as{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
  VkPhysicalDeviceRayTracingPipelineFeaturesKHR rt{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_FEATURES_KHR, &as};
  VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &rt};
  vkGetPhysicalDeviceFeatures2(pd, &f2);
  if (!as.accelerationStructure) return "the device reports accelerationStructure = false";
  if (!rt.rayTracingPipeline) return "the device reports rayTracingPipeline = false";
  return {};
}

}  // namespace

Device::Device(const DeviceOptions& options) {
  timeoutSeconds_ = watchdogSeconds(options);
  createInstance(options);
  choosePhysicalDevice(options);
  createLogicalDevice(options);
}

VkDescriptorSetLayout Device::sharedSetLayout(const std::string& key, const VkDescriptorSetLayoutCreateInfo& info) {
  auto [it, added] = sharedSetLayouts_.try_emplace(key, VK_NULL_HANDLE);
  if (added) {
    try {
      TL_VK(vkCreateDescriptorSetLayout(device_, &info, nullptr, &it->second));
    } catch (...) {
      sharedSetLayouts_.erase(it);
      throw;
    }
  }
  return it->second;
}

VkSampler Device::sampler(const SamplerDesc& desc) {
  auto [it, added] = samplers_.try_emplace(desc.key(), VK_NULL_HANDLE);
  if (added) {
    VkSamplerCreateInfo ci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    ci.magFilter = ci.minFilter = desc.filter;
    ci.mipmapMode = desc.filter == VK_FILTER_LINEAR ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST;
    ci.addressModeU = ci.addressModeV = ci.addressModeW = desc.address;
    ci.maxLod = VK_LOD_CLAMP_NONE;
    ci.borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
    ci.compareEnable = desc.compareDepth;
    ci.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
    try {
      TL_VK(vkCreateSampler(device_, &ci, nullptr, &it->second));
    } catch (...) {
      samplers_.erase(it);
      throw;
    }
    setName(VK_OBJECT_TYPE_SAMPLER, uint64_t(it->second), desc.name);
  }
  return it->second;
}

PipelineCache& Device::pipelines() {
  if (!pipelines_) pipelines_ = std::make_unique<PipelineCache>();
  return *pipelines_;
}

Device::~Device() {
  if (device_) {
    waitTimeline(submitted_);  // a device that hangs stops the process here, not in vkDeviceWaitIdle
    vkDeviceWaitIdle(device_);
    pipelines_.reset();  // hands its objects to the garbage below
    for (auto& g : garbage_) g.destroy();
    garbage_.clear();
    for (auto& [key, layout] : sharedSetLayouts_) vkDestroyDescriptorSetLayout(device_, layout, nullptr);
    for (auto& [key, sampler] : samplers_) vkDestroySampler(device_, sampler, nullptr);
    for (auto& s : commandSlots_) vkDestroyCommandPool(device_, s.pool, nullptr);
    vkDestroySemaphore(device_, timeline_, nullptr);
    vkDestroyDevice(device_, nullptr);
  }
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance_, messenger_, nullptr);
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
}

void Device::createInstance(const DeviceOptions& options) {
  validation_ = options.validation || envFlag("TWINLIGHT_VALIDATION");

  uint32_t n = 0;
  vkEnumerateInstanceExtensionProperties(nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> available(n);
  vkEnumerateInstanceExtensionProperties(nullptr, &n, available.data());
  auto hasExt = [&](const char* e) {
    return std::any_of(available.begin(), available.end(), [&](auto& p) { return !std::strcmp(p.extensionName, e); });
  };

  std::vector<const char*> exts;
  for (auto& e : options.instanceExtensions) exts.push_back(e.c_str());
  debugUtils_ = hasExt(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  if (debugUtils_) exts.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);

  std::vector<const char*> layers;
  if (validation_) {
    vkEnumerateInstanceLayerProperties(&n, nullptr);
    std::vector<VkLayerProperties> lp(n);
    vkEnumerateInstanceLayerProperties(&n, lp.data());
    bool found = std::any_of(lp.begin(), lp.end(),
                             [](auto& l) { return !std::strcmp(l.layerName, "VK_LAYER_KHRONOS_validation"); });
    if (!found) throw Error("validation was requested but VK_LAYER_KHRONOS_validation is not installed (package vulkan-validationlayers)");
    layers.push_back("VK_LAYER_KHRONOS_validation");
    // The layer provides the extension whose struct switches synchronization validation on.
    uint32_t count = 0;
    vkEnumerateInstanceExtensionProperties("VK_LAYER_KHRONOS_validation", &count, nullptr);
    std::vector<VkExtensionProperties> layerExts(count);
    vkEnumerateInstanceExtensionProperties("VK_LAYER_KHRONOS_validation", &count, layerExts.data());
    const bool features = std::any_of(layerExts.begin(), layerExts.end(), [](auto& p) {
      return !std::strcmp(p.extensionName, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
    });
    if (!features)
      throw Error("validation was requested but the validation layer lacks " VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME
                  " (synchronization validation)");
    exts.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
  }

  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "Twinlight";
  app.pEngineName = "Twinlight";
  app.apiVersion = VK_API_VERSION_1_3;

  VkDebugUtilsMessengerCreateInfoEXT dbg{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  dbg.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  dbg.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                    VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  dbg.pfnUserCallback = &Device::debugCallback;
  dbg.pUserData = this;

  // With validation on, synchronization validation is on too: a missing barrier is a
  // validation error like any other (SYNC-HAZARD-* messages have error severity), so every
  // GPU, CLI and editor test checks the render graph's barriers.
  const VkValidationFeatureEnableEXT syncValidation = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = &syncValidation;
  features.pNext = debugUtils_ ? &dbg : nullptr;

  VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ci.pApplicationInfo = &app;
  ci.enabledExtensionCount = uint32_t(exts.size());
  ci.ppEnabledExtensionNames = exts.data();
  ci.enabledLayerCount = uint32_t(layers.size());
  ci.ppEnabledLayerNames = layers.data();
  if (validation_) ci.pNext = &features;
  VkResult r = vkCreateInstance(&ci, nullptr, &instance_);
  if (r == VK_ERROR_INCOMPATIBLE_DRIVER)
    throw Error("no Vulkan 1.3 driver found (install mesa-vulkan-drivers for lavapipe, or a GPU driver)");
  TL_VK(r);
#ifdef TWINLIGHT_SANITIZE
  keepLoadedLibrariesLoaded();  // the driver and layers stay mapped until LeakSanitizer reports
#endif

  if (validation_ && debugUtils_) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    TL_VK(create(instance_, &dbg, nullptr, &messenger_));
  }
}

void Device::choosePhysicalDevice(const DeviceOptions& options) {
  uint32_t n = 0;
  TL_VK(vkEnumeratePhysicalDevices(instance_, &n, nullptr));
  std::vector<VkPhysicalDevice> devices(n);
  TL_VK(vkEnumeratePhysicalDevices(instance_, &n, devices.data()));
  if (devices.empty()) throw Error("no Vulkan device found (install mesa-vulkan-drivers for lavapipe)");

  std::string wanted = options.preferredName;
  if (const char* env = std::getenv("TWINLIGHT_DEVICE"); env && *env) wanted = env;

  std::vector<std::string> names;
  int best = -1, bestScore = -1;
  for (size_t i = 0; i < devices.size(); ++i) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(devices[i], &p);
    names.emplace_back(p.deviceName);
    if (p.apiVersion < VK_API_VERSION_1_3) continue;
    if (!wanted.empty()) {
      if (lower(p.deviceName).find(lower(wanted)) != std::string::npos && best < 0) best = int(i);
      continue;
    }
    // Prefer ray tracing first, then a real GPU over a software one.
    int score = (rayTracingMissing(devices[i]).empty() ? 4 : 0) +
                (p.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU     ? 2
                 : p.deviceType == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU ? 1
                                                                          : 0);
    if (score > bestScore) bestScore = score, best = int(i);
  }
  if (best < 0) {
    std::string list;
    for (auto& s : names) list += (list.empty() ? "" : ", ") + s;
    const char* why = RenderDoc::get().attached() ? "; RenderDoc is attached: it offers Vulkan 1.3 only on devices with "
                                                    "bufferDeviceAddressCaptureReplay (lavapipe has none), else 1.2"
                                                  : "";
    if (!wanted.empty())
      throw Error(fmt::format("TWINLIGHT_DEVICE=\"{}\" matches no Vulkan 1.3 device (found: {}){}", wanted, list, why));
    throw Error(fmt::format("no Vulkan 1.3 device found (found: {}){}", list, why));
  }
  physical_ = devices[best];

  VkPhysicalDeviceMaintenance3Properties maintenance3{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES};
  VkPhysicalDeviceDriverProperties driverProps{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES, &maintenance3};
  VkPhysicalDeviceRayTracingPipelinePropertiesKHR rtProps{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_PROPERTIES_KHR, &driverProps};
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &rtProps};
  vkGetPhysicalDeviceProperties2(physical_, &props);
  name_ = props.properties.deviceName;
  driver_ = fmt::format("{} {}", driverProps.driverName, driverProps.driverInfo);
  apiVersion_ = props.properties.apiVersion;
  limits_ = props.properties.limits;
  maxAllocationSize_ = maintenance3.maxMemoryAllocationSize;
  vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);

  rayTracing_.unavailableReason = rayTracingMissing(physical_);
  rayTracing_.pipeline = rayTracing_.unavailableReason.empty();
  rayTracing_.pipelineProperties = rtProps;
  rayTracing_.pipelineProperties.pNext = nullptr;
  if (envFlag("TWINLIGHT_NO_RAY_TRACING")) {  // lets tests and users exercise the fallback
    rayTracing_.pipeline = false;
    rayTracing_.unavailableReason = "ray tracing was switched off with TWINLIGHT_NO_RAY_TRACING";
  }
}

void Device::createLogicalDevice(const DeviceOptions& options) {
  uint32_t n = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &n, nullptr);
  std::vector<VkQueueFamilyProperties> families(n);
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &n, families.data());
  bool found = false;
  for (uint32_t i = 0; i < n; ++i) {
    auto f = families[i].queueFlags;
    if ((f & VK_QUEUE_GRAPHICS_BIT) && (f & VK_QUEUE_COMPUTE_BIT)) {
      queueFamily_ = i;
      found = true;
      break;
    }
  }
  if (!found) throw Error(fmt::format("device {} has no graphics+compute queue", name_));

  auto available = deviceExtensions(physical_);
  std::vector<const char*> exts{VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
  if (!available.count(VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME))
    throw Error(fmt::format("device {} lacks {}", name_, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME));
  if (options.swapchain) exts.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  rayTracing_.query = rayTracing_.pipeline && available.count(VK_KHR_RAY_QUERY_EXTENSION_NAME);
  if (rayTracing_.pipeline) {
    exts.push_back(VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME);
    exts.push_back(VK_KHR_RAY_TRACING_PIPELINE_EXTENSION_NAME);
    exts.push_back(VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME);
  }
  if (rayTracing_.query) exts.push_back(VK_KHR_RAY_QUERY_EXTENSION_NAME);

  // Query what the device has, then require the core set and switch on the optional ones.
  VkPhysicalDeviceRayQueryFeaturesKHR rq{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
  VkPhysicalDeviceAccelerationStructureFeaturesKHR as{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
  VkPhysicalDeviceRayTracingPipelineFeaturesKHR rt{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_FEATURES_KHR};
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f13};
  VkPhysicalDeviceVulkan11Features f11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES, &f12};
  VkPhysicalDeviceFeatures2 have{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f11};
  vkGetPhysicalDeviceFeatures2(physical_, &have);

  auto require = [&](VkBool32 v, const char* what) {
    if (!v) throw Error(fmt::format("device {} lacks the required feature {}", name_, what));
    return VkBool32(VK_TRUE);
  };
  VkPhysicalDeviceVulkan13Features e13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  e13.synchronization2 = require(f13.synchronization2, "synchronization2");
  e13.dynamicRendering = require(f13.dynamicRendering, "dynamicRendering");
  e13.maintenance4 = f13.maintenance4;
  VkPhysicalDeviceVulkan12Features e12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &e13};
  e12.timelineSemaphore = require(f12.timelineSemaphore, "timelineSemaphore");
  e12.bufferDeviceAddress = require(f12.bufferDeviceAddress, "bufferDeviceAddress");
  e12.descriptorIndexing = f12.descriptorIndexing;
  e12.runtimeDescriptorArray = require(f12.runtimeDescriptorArray, "runtimeDescriptorArray");
  e12.descriptorBindingPartiallyBound = require(f12.descriptorBindingPartiallyBound, "descriptorBindingPartiallyBound");
  e12.descriptorBindingVariableDescriptorCount = f12.descriptorBindingVariableDescriptorCount;
  e12.shaderSampledImageArrayNonUniformIndexing =
      require(f12.shaderSampledImageArrayNonUniformIndexing, "shaderSampledImageArrayNonUniformIndexing");
  e12.scalarBlockLayout = f12.scalarBlockLayout;
  e12.shaderFloat16 = f12.shaderFloat16;
  e12.hostQueryReset = f12.hostQueryReset;
  VkPhysicalDeviceVulkan11Features e11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES, &e12};
  e11.storageBuffer16BitAccess = f11.storageBuffer16BitAccess;
  VkPhysicalDeviceFeatures2 enable{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &e11};
  enable.features.shaderInt64 = have.features.shaderInt64;
  enable.features.shaderInt16 = have.features.shaderInt16;
  enable.features.fragmentStoresAndAtomics = have.features.fragmentStoresAndAtomics;
  enable.features.shaderStorageImageWriteWithoutFormat = have.features.shaderStorageImageWriteWithoutFormat;
  enable.features.shaderStorageImageReadWithoutFormat = have.features.shaderStorageImageReadWithoutFormat;
  enable.features.samplerAnisotropy = have.features.samplerAnisotropy;
  enable.features.depthClamp = have.features.depthClamp;
  enable.features.depthBiasClamp = have.features.depthBiasClamp;
  enable.features.independentBlend = have.features.independentBlend;
  enable.features.geometryShader = have.features.geometryShader;
  multiDrawIndirect_ = have.features.multiDrawIndirect && have.features.drawIndirectFirstInstance;
  enable.features.multiDrawIndirect = enable.features.drawIndirectFirstInstance = multiDrawIndirect_;

  void** tail = &e13.pNext;
  if (rayTracing_.pipeline) {
    VkPhysicalDeviceFeatures2 q{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &as};
    as.pNext = &rt;
    rt.pNext = rayTracing_.query ? static_cast<void*>(&rq) : nullptr;
    vkGetPhysicalDeviceFeatures2(physical_, &q);
    rt.rayTracingPipelineTraceRaysIndirect = VK_FALSE;
    rt.rayTraversalPrimitiveCulling = VK_FALSE;
    as.accelerationStructureCaptureReplay = as.accelerationStructureIndirectBuild = VK_FALSE;
    as.accelerationStructureHostCommands = VK_FALSE;
    rt.rayTracingPipelineShaderGroupHandleCaptureReplay = VK_FALSE;
    rt.rayTracingPipelineShaderGroupHandleCaptureReplayMixed = VK_FALSE;
    *tail = &as;
    tail = rayTracing_.query ? &rq.pNext : &rt.pNext;
  }
  *tail = nullptr;

  float priority = 1.0f;
  VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qci.queueFamilyIndex = queueFamily_;
  qci.queueCount = 1;
  qci.pQueuePriorities = &priority;
  VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &enable};
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  dci.enabledExtensionCount = uint32_t(exts.size());
  dci.ppEnabledExtensionNames = exts.data();
  TL_VK(vkCreateDevice(physical_, &dci, nullptr, &device_));
  vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);

  auto load = [&](auto& fn, const char* name) { fn = reinterpret_cast<std::decay_t<decltype(fn)>>(vkGetDeviceProcAddr(device_, name)); };
  load(ext_.cmdPushDescriptorSet, "vkCmdPushDescriptorSetKHR");
  if (debugUtils_) {
    ext_.setObjectName = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(vkGetInstanceProcAddr(instance_, "vkSetDebugUtilsObjectNameEXT"));
    ext_.cmdBeginLabel = reinterpret_cast<PFN_vkCmdBeginDebugUtilsLabelEXT>(vkGetInstanceProcAddr(instance_, "vkCmdBeginDebugUtilsLabelEXT"));
    ext_.cmdEndLabel = reinterpret_cast<PFN_vkCmdEndDebugUtilsLabelEXT>(vkGetInstanceProcAddr(instance_, "vkCmdEndDebugUtilsLabelEXT"));
  }
  if (rayTracing_.pipeline) {
    load(ext_.createAccelerationStructure, "vkCreateAccelerationStructureKHR");
    load(ext_.destroyAccelerationStructure, "vkDestroyAccelerationStructureKHR");
    load(ext_.getAccelerationStructureBuildSizes, "vkGetAccelerationStructureBuildSizesKHR");
    load(ext_.cmdBuildAccelerationStructures, "vkCmdBuildAccelerationStructuresKHR");
    load(ext_.getAccelerationStructureDeviceAddress, "vkGetAccelerationStructureDeviceAddressKHR");
    load(ext_.cmdWriteAccelerationStructuresProperties, "vkCmdWriteAccelerationStructuresPropertiesKHR");
    load(ext_.cmdCopyAccelerationStructure, "vkCmdCopyAccelerationStructureKHR");
    load(ext_.createRayTracingPipelines, "vkCreateRayTracingPipelinesKHR");
    load(ext_.getRayTracingShaderGroupHandles, "vkGetRayTracingShaderGroupHandlesKHR");
    load(ext_.cmdTraceRays, "vkCmdTraceRaysKHR");
  }

  VkSemaphoreTypeCreateInfo type{VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO};
  type.semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE;
  VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO, &type};
  TL_VK(vkCreateSemaphore(device_, &sci, nullptr, &timeline_));
  setName(VK_OBJECT_TYPE_SEMAPHORE, uint64_t(timeline_), "device.timeline");

  spdlog::info("Vulkan device: {} ({}), ray tracing: {}", name_, driver_,
               rayTracing_.pipeline ? (rayTracing_.query ? "pipeline + query" : "pipeline")
                                    : rayTracing_.unavailableReason);
}

VkBool32 Device::debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
                               const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  auto* self = static_cast<Device*>(user);
  const char* msg = data && data->pMessage ? data->pMessage : "";
  if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
    self->validationErrors_++;
    spdlog::error("validation: {}", msg);
    std::lock_guard lock(self->messagesMutex_);
    if (self->messages_.size() < 64) self->messages_.emplace_back(msg);
  } else {
    spdlog::debug("validation: {}", msg);
  }
  return VK_FALSE;
}

std::vector<std::string> Device::validationMessages() const {
  std::lock_guard lock(messagesMutex_);
  return messages_;
}

uint32_t Device::findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred) const {
  for (int pass = 0; pass < 2; ++pass) {
    VkMemoryPropertyFlags want = pass == 0 ? required | preferred : required;
    for (uint32_t i = 0; i < memory_.memoryTypeCount; ++i) {
      if ((typeBits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & want) == want) return i;
    }
  }
  throw Error(fmt::format("no memory type with flags {:#x} among bits {:#x}", required, typeBits));
}

void Device::reserveMemory(uint32_t memoryType, VkDeviceSize bytes, std::string_view name) {
  const auto gib = [](VkDeviceSize b) { return double(b) / double(1ull << 30); };
  if (maxAllocationSize_ && bytes > maxAllocationSize_)
    throw Error(fmt::format("`{}` needs {:.2f} GiB in one allocation, more than the {:.2f} GiB {} allows "
                            "(maxMemoryAllocationSize); a smaller image size fits",
                            name, gib(bytes), gib(maxAllocationSize_), name_));
  const uint32_t heap = memory_.memoryTypes[memoryType].heapIndex;
  const VkDeviceSize heapSize = memory_.memoryHeaps[heap].size;
  const VkDeviceSize inUse = allocated_[heap].load();
  if (inUse + bytes > heapSize)
    throw Error(fmt::format("`{}` needs {:.2f} GiB more, with {:.2f} GiB of the {:.2f} GiB memory heap of {} in use; "
                            "a smaller image size fits",
                            name, gib(bytes), gib(inUse), gib(heapSize), name_));
  allocated_[heap] += bytes;
  ++allocationsMade_;
}

void Device::releaseMemory(uint32_t memoryType, VkDeviceSize bytes) {
  allocated_[memory_.memoryTypes[memoryType].heapIndex] -= bytes;
}

VkCommandBuffer Device::beginCommands() {
  collectGarbage();
  uint64_t done = completedValue();
  CommandSlot* slot = nullptr;
  for (auto& s : commandSlots_) {
    if (!s.recording && s.value <= done) {
      slot = &s;
      break;
    }
  }
  if (!slot) {
    CommandSlot s;
    VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pci.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    pci.queueFamilyIndex = queueFamily_;
    TL_VK(vkCreateCommandPool(device_, &pci, nullptr, &s.pool));
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = s.pool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    TL_VK(vkAllocateCommandBuffers(device_, &ai, &s.cmd));
    commandSlots_.push_back(s);
    slot = &commandSlots_.back();
  }
  TL_VK(vkResetCommandPool(device_, slot->pool, 0));
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  TL_VK(vkBeginCommandBuffer(slot->cmd, &bi));
  slot->recording = true;
  return slot->cmd;
}

uint64_t Device::submit(VkCommandBuffer cmd, const std::vector<VkSemaphoreSubmitInfo>& waits,
                        const std::vector<VkSemaphoreSubmitInfo>& signals) {
  TL_VK(vkEndCommandBuffer(cmd));
  uint64_t value = ++submitted_;
  std::vector<VkSemaphoreSubmitInfo> sig = signals;
  VkSemaphoreSubmitInfo t{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  t.semaphore = timeline_;
  t.value = value;
  t.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  sig.push_back(t);
  VkCommandBufferSubmitInfo cb{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cb.commandBuffer = cmd;
  VkSubmitInfo2 si{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  si.waitSemaphoreInfoCount = uint32_t(waits.size());
  si.pWaitSemaphoreInfos = waits.data();
  si.commandBufferInfoCount = 1;
  si.pCommandBufferInfos = &cb;
  si.signalSemaphoreInfoCount = uint32_t(sig.size());
  si.pSignalSemaphoreInfos = sig.data();
  VkResult r = vkQueueSubmit2(queue_, 1, &si, VK_NULL_HANDLE);
  if (r == VK_ERROR_DEVICE_LOST) throw Error(fmt::format("device lost on {} — the GPU stopped responding", name_));
  TL_VK(r);
  for (auto& s : commandSlots_) {
    if (s.cmd == cmd) {
      s.recording = false;
      s.value = value;
    }
  }
  return value;
}

uint64_t Device::completedValue() const {
  uint64_t v = 0;
  TL_VK(vkGetSemaphoreCounterValue(device_, timeline_, &v));
  return v;
}

void Device::waitTimeline(uint64_t value) {
  VkSemaphoreWaitInfo wi{VK_STRUCTURE_TYPE_SEMAPHORE_WAIT_INFO};
  wi.semaphoreCount = 1;
  wi.pSemaphores = &timeline_;
  wi.pValues = &value;
  VkResult r = vkWaitSemaphores(device_, &wi, uint64_t(timeoutSeconds_ * 1e9));
  if (r == VK_TIMEOUT) {
    // Unrecoverable: the device still runs the work, so nothing it uses may be freed and no
    // later wait would end. One line, and the process stops (STYLE.md: two error policies).
    fmt::print(stderr,
               "twinlight: error: {} did not finish the GPU work it was given within {:g} s (the watchdog, "
               "TWINLIGHT_GPU_TIMEOUT); stopping\n",
               name_, timeoutSeconds_);
    std::fflush(stderr);
    std::_Exit(kExitDeviceHung);
  }
  if (r == VK_ERROR_DEVICE_LOST) throw Error(fmt::format("device lost on {} — the GPU stopped responding", name_));
  TL_VK(r);
}

void Device::wait(uint64_t value) {
  waitTimeline(value);
  collectGarbage();
}

void Device::waitIdle() {
  waitTimeline(submitted_);  // bounded by the watchdog; then the idle wait returns at once
  TL_VK(vkDeviceWaitIdle(device_));
  collectGarbage();
}

void Device::immediate(const std::function<void(VkCommandBuffer)>& record) {
  VkCommandBuffer cmd = beginCommands();
  record(cmd);
  wait(submit(cmd));
}

void Device::destroyLater(std::function<void()> destroy) {
  // Anything recorded so far, including a command buffer being recorded now, may use it.
  garbage_.push_back({submitted_ + 1, std::move(destroy)});
}

void Device::collectGarbage() {
  uint64_t done = completedValue();
  bool idle = std::none_of(commandSlots_.begin(), commandSlots_.end(), [](auto& s) { return s.recording; });
  while (!garbage_.empty() && (garbage_.front().after <= done || (idle && garbage_.front().after == submitted_ + 1 && done == submitted_))) {
    garbage_.front().destroy();
    garbage_.pop_front();
  }
}

void Device::setName(VkObjectType type, uint64_t handle, std::string_view name) const {
  if (!ext_.setObjectName || !handle) return;
  std::string n(name);
  VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
  info.objectType = type;
  info.objectHandle = handle;
  info.pObjectName = n.c_str();
  ext_.setObjectName(device_, &info);
}

void Device::beginLabel(VkCommandBuffer cmd, std::string_view label) const {
  if (!ext_.cmdBeginLabel) return;
  std::string n(label);
  VkDebugUtilsLabelEXT l{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
  l.pLabelName = n.c_str();
  ext_.cmdBeginLabel(cmd, &l);
}

void Device::endLabel(VkCommandBuffer cmd) const {
  if (ext_.cmdEndLabel) ext_.cmdEndLabel(cmd);
}

}  // namespace tl::gpu
