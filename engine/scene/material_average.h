// One colour per material, from texture averages: the RT path's hit albedo and emission
// when nothing better is known (the albedo database bakes a visible average; artists override).
#pragma once

#include "scene/scene.h"
#include "shared/material_mode.h"

#include <glm/glm.hpp>

namespace tl::scene {

// Average of a texture's texels in linear space (sRGB decoded when the texture is colour).
glm::vec4 textureAverage(const Texture& texture);

// Base colour factor times its texture's average, through Metro's albedo (1 - F0) + F0 rule
// (shared/rt.h) so metals bounce their specular colour; under a material override mode
// (shared/material_mode.h kMaterials*) what that mode reflects: the base colour (diffuse) or
// the clay albedo.
glm::vec3 materialAverageAlbedo(const Scene& scene, const Material& material,
                                uint32_t materials = shared::kMaterialsAuthored);
// Emissive factor x strength x the emissive texture's average.
glm::vec3 materialAverageEmission(const Scene& scene, const Material& material);

}  // namespace tl::scene
