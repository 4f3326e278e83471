// The light table every path shades (shaders/shared/lights.h GpuLight): the scene's lights
// other than the sun, on Twinlight's radiometric scale, positions relative to the camera, each
// with the probability that many-light sampling draws it. Pure, tested without a GPU.
#pragma once

#include "graph/resource_name.h"
#include "scene/scene.h"
#include "shared/lights.h"

#include <glm/glm.hpp>

#include <vector>

namespace tl::lighting {

// The graph's name of the imported table (only in frames whose scene has such lights).
inline constexpr graph::BufferName kLightTable{"lights.table"};

// The power a light is drawn in proportion to (luminance, Twinlight units): 4 pi I for a point
// light, I times the outer cone's solid angle for a spot, and for a directional light its
// irradiance over a disc the size of the scene (sceneScale: the scene's diagonal, metres); pi L A
// for an area light's emitting faces (a tube: its side, 2 pi r length).
double lightSelectionPower(const scene::Light& light, double sceneScale);

// Lights that emit nothing and hidden lights are left out. Cumulative probabilities end at exactly 1.
std::vector<shared::GpuLight> buildLightTable(const std::vector<scene::Light>& lights, const glm::dvec3& cameraWorld,
                                              double sceneScale);

}  // namespace tl::lighting
