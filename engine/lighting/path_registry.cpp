#include "lighting/lighting_path.h"

namespace tl::lighting {
namespace {

std::vector<LightingPathFactory>& registry() {
  static std::vector<LightingPathFactory> paths = {makeDirectPath, makeLegacyPath, makeRtPath, makeReferencePath};
  return paths;
}

}  // namespace

std::optional<std::string> LightingPath::unavailableReason(const gpu::Device& device) const {
  if (capabilities().needsRayTracing && !device.rayTracing().pipeline)
    return "needs hardware or lavapipe ray tracing: " + device.rayTracing().unavailableReason;
  return std::nullopt;
}

const std::vector<LightingPathFactory>& lightingPathRegistry() { return registry(); }

void registerLightingPath(LightingPathFactory factory) {
  for (LightingPathFactory f : registry())
    if (f == factory) return;
  registry().push_back(factory);
}

}  // namespace tl::lighting
