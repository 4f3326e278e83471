// glTF lights: KHR_lights_punctual lights, the sun (the first directional light) and the sky
// radiance Twinlight keeps in the file's extras.
#include "scene/gltf_parts.h"

namespace tl::scene {

// One KHR_lights_punctual light at its node's place. One rule with the rest of the import
// (ImportValues): a plain value out of range is clamped with one warning naming the light
// (negative light does not exist: 0), a value that is not a finite float or beyond the light
// limit is one error, and data the specification forbids (an unknown type, a colour of other
// than 3 numbers, cones with inner >= outer or outside [0, pi/2]) is one error, not a guess.
// Returns nothing, with a warning, when the node's transform leaves no direction.
std::optional<Light> readLight(const tinygltf::Light& gl, const std::string& nodeName, const glm::dvec3& position,
                               const glm::dquat& orientation, ImportValues& values) {
  Light l;
  l.name = gl.name.empty() ? nodeName : gl.name;
  const std::string what = fmt::format("light `{}`", l.name);
  if (gl.type == "directional") l.type = LightType::Directional;
  else if (gl.type == "point") l.type = LightType::Point;
  else if (gl.type == "spot") l.type = LightType::Spot;
  else values.fail(fmt::format("{} has type `{}` (KHR_lights_punctual: directional, point or spot)", what, gl.type));
  l.color = values.lightColor(gl.color, l.color, what + " color");
  l.intensity = values.light(gl.intensity, what + " intensity");
  values.requireLightRange(l.color * l.intensity, what + " (color x intensity)");
  if (gl.range > 0 && std::isfinite(float(gl.range))) l.range = float(gl.range);
  if (l.type == LightType::Spot) {
    l.innerConeAngle = values.finite(gl.spot.innerConeAngle, what + " innerConeAngle");
    l.outerConeAngle = values.finite(gl.spot.outerConeAngle, what + " outerConeAngle");
    if (!(l.innerConeAngle >= 0.0f && l.innerConeAngle < l.outerConeAngle && l.outerConeAngle <= 0.5f * glm::pi<float>() + 1e-6f))
      values.fail(fmt::format("{} has cone angles inner {} and outer {} (0 <= inner < outer <= pi/2)", what,
                              l.innerConeAngle, l.outerConeAngle));
  }
  l.position = position;
  l.direction = glm::normalize(orientation * glm::dvec3(0.0, 0.0, -1.0));
  if (allFinite(l.direction)) return l;
  values.warn(fmt::format("{} has no direction (its node's transform is singular); it is ignored", what));
  return std::nullopt;
}

void readEnvironment(GltfImport& in, size_t sceneIndex) {
  Scene& scene = in.scene;
  const GltfReader& rd = in.rd;
  ImportValues& values = in.values;
  // Environment: the first directional light is the sun; the others are shaded from the light table.
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& l = scene.lights[i];
    if (l.type != LightType::Directional) continue;
    scene.environment.sunDirection = l.direction;
    scene.environment.sunIrradiance = l.radiometric();
    scene.environment.sunFromFile = true;
    scene.environment.sunLight = i;
    break;
  }
  auto readSky = [&](const tinygltf::Value& extras) {
    if (!extras.IsObject() || !extras.Has("twinlight")) return;
    const auto& t = extras.Get("twinlight");
    const auto& sky = t.Get("sky_radiance");
    if (sky.IsArray() && sky.ArrayLen() == 3) {
      glm::vec3 c;
      for (int k = 0; k < 3; ++k) {
        const auto& v = sky.Get(k);
        if (!v.IsNumber() || v.GetNumberAsDouble() < 0.0) rd.fail("extras.twinlight.sky_radiance must be three non-negative numbers");
        c[k] = values.finite(v.GetNumberAsDouble(), "extras.twinlight.sky_radiance");
      }
      values.requireLightRange(c, "extras.twinlight.sky_radiance");
      scene.environment.skyRadiance = c;
    }
  };
  readSky(in.model.extras);
  if (!in.model.scenes.empty()) readSky(in.model.scenes[sceneIndex].extras);
}

}  // namespace tl::scene
