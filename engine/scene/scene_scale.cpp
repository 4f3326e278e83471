#include "scene/scene_scale.h"

#include <glm/gtc/matrix_transform.hpp>

namespace tl::scene {

void scaleLight(Light& l, double factor) {
  const float f = float(factor);
  l.position *= factor;
  if (l.range) *l.range *= f;
  l.width *= f, l.height *= f, l.radius *= f, l.length *= f;
  // Intensity (candela) falls off as 1/d^2: the same irradiance at factor times the distance.
  if (l.type == LightType::Point || l.type == LightType::Spot) l.intensity *= f * f;
}

void scaleScene(Scene& scene, double factor) {
  const glm::dmat4 scale = glm::scale(glm::dmat4(1.0), glm::dvec3(factor));
  for (Node& n : scene.nodes) {
    if (n.parent >= 0) continue;  // children follow their root
    if (n.matrix) {
      n.matrix = scale * *n.matrix;
    } else {  // uniform scale commutes with the rotation: T R S -> (f T) R (f S)
      n.translation *= factor;
      n.scale *= factor;
    }
  }
  for (NodeAnimation& a : scene.nodeAnimations) {
    if (a.property == NodeProperty::Rotation || scene.nodes.at(a.node).parent >= 0) continue;
    for (glm::dvec4& v : a.values) v = glm::dvec4(glm::dvec3(v) * factor, v.w);
  }
  for (Instance& i : scene.instances) {
    i.transform = scale * i.transform;
    if (i.worldBounds.valid()) i.worldBounds.min *= factor, i.worldBounds.max *= factor;
  }
  if (scene.bounds.valid()) scene.bounds.min *= factor, scene.bounds.max *= factor;
  for (Camera& c : scene.cameras) {
    c.position *= factor;
    c.znear *= float(factor);
    if (c.zfar) *c.zfar *= float(factor);
    c.xmag *= float(factor), c.ymag *= float(factor);
  }
  for (Light& l : scene.lights) scaleLight(l, factor);
  // A volume's attenuation distance is a length in the world (KHR_materials_volume); its
  // thickness is in the mesh's space, which the nodes already scale.
  for (Material& m : scene.materials) m.attenuationDistance *= float(factor);
  // Another scene as far as every history is concerned.
  scene.contentHash = hashBytes(&factor, sizeof factor, scene.contentHash);
}

}  // namespace tl::scene
