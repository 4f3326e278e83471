// The same scene at another size: what a scale-free renderer must draw the same. Every length
// is multiplied by `factor` (where nodes place meshes, cameras' positions, near and far planes
// and orthographic extents, lights' positions, ranges and area sizes, volumes' attenuation
// distances, the bounds) and point and spot intensities by factor^2, so the irradiance each
// surface receives from them at its scaled distance is unchanged; the sun's irradiance, the
// sky's and the area lights' radiance and emission hold no length. Meshes keep their vertices: the roots of the node
// hierarchy (and their animation keys) take the factor, so animation, skinning and motion follow.
#pragma once

#include "scene/scene.h"

namespace tl::scene {

void scaleScene(Scene& scene, double factor);
// One light as scaleScene scales it (for lights held outside a Scene: a lighting file's).
void scaleLight(Light& light, double factor);

}  // namespace tl::scene
