#include "gpu/self_test.h"

#include "gpu/acceleration_structure.h"
#include "gpu/pipeline.h"
#include "shared/selftest.h"

#include <fmt/format.h>

#include <cmath>
#include <cstring>

namespace tl::gpu {

std::optional<std::string> rayTracingSelfTest(Device& device) {
  if (!device.rayTracing().pipeline) return "ray tracing is unavailable: " + device.rayTracing().unavailableReason;
  using namespace shared;
  try {
    const float vertices[9] = {-1.0f, -1.0f, 0.0f, 1.01f, -1.0f, 0.0f, -1.0f, 1.01f, 0.0f};
    const uint32_t indices[3] = {0, 1, 2};
    const VkBufferUsageFlags input = VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR;
    Buffer vb(device, sizeof vertices, input, MemoryUsage::Upload, "selftest.vertices");
    Buffer ib(device, sizeof indices, input, MemoryUsage::Upload, "selftest.indices");
    vb.write(vertices, sizeof vertices);
    ib.write(indices, sizeof indices);
    AccelerationStructure blas = buildBottomLevel(device, {vb.address(), 12, 3, ib.address(), 1, true}, "selftest.blas");
    AccelerationStructure tlas = buildTopLevel(device, {{glm::mat4(1.0f), 0, 0xFF, blas.address()}}, "selftest.tlas");

    RayTracingPipelineDesc d;
    d.name = "selftest.trace";
    d.raygen = "selftest/trace.rgen";
    d.misses = {"selftest/trace.rmiss"};
    d.hitGroups = {{"selftest/trace.rchit", ""}};
    d.layout.bindings = {{kSelfTestBindingScene, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR},
                         {kSelfTestBindingOutput, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}};
    Pipeline pipeline = createRayTracingPipeline(device, d);
    Image out(device, {VK_FORMAT_R32_SFLOAT, {kSelfTestSize, kSelfTestSize, 1}, 1, VK_IMAGE_USAGE_STORAGE_BIT},
              "selftest.result");
    device.immediate([&](VkCommandBuffer cmd) {
      transitionImage(cmd, out, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
      vkCmdBindPipeline(cmd, pipeline.bindPoint(), pipeline.handle());
      DescriptorWriter().accelerationStructure(kSelfTestBindingScene, tlas.handle())
          .storageImage(kSelfTestBindingOutput, out.view())
          .push(device, cmd, pipeline);
      device.ext().cmdTraceRays(cmd, &pipeline.raygenRegion, &pipeline.missRegion, &pipeline.hitRegion,
                                &pipeline.callableRegion, kSelfTestSize, kSelfTestSize, 1);
    });
    auto bytes = readbackImage(device, out, VK_IMAGE_LAYOUT_GENERAL);
    for (uint32_t y = 0; y < kSelfTestSize; ++y)
      for (uint32_t x = 0; x < kSelfTestSize; ++x) {
        float got;
        std::memcpy(&got, &bytes[(y * kSelfTestSize + x) * 4], 4);
        vec2 xy = tlSelfTestRayXY(x, y);
        float want = xy.x + xy.y < 0.01f ? 1.0f : kSelfTestMiss;
        if (std::abs(got - want) > 1e-4f)
          return fmt::format("ray ({}, {}) returned {} instead of {}", x, y, got, want);
      }
  } catch (const std::exception& e) {
    return std::string("the ray-tracing self-test failed: ") + e.what();
  }
  return std::nullopt;
}

}  // namespace tl::gpu
