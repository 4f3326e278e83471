#include "session/view_math.h"

#include "lighting/common/frame_key.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace tl::session {

CameraMatrices cameraMatrices(const View& v, double aspect) {
  CameraMatrices m;
  m.view = glm::lookAtRH(glm::dvec3(0.0), v.forward, v.up);
  m.proj = glm::dmat4(0.0);
  if (v.orthographic) {
    // Reversed Z as for the perspective: z_ndc = (far - d) / (far - near) at distance d along
    // the view axis, 1 at the near plane and 0 at the far one; w = 1.
    const double h = double(v.orthoHalfHeight), n = double(v.znear), far = double(v.zfar);
    m.proj[0][0] = 1.0 / (h * aspect);
    m.proj[1][1] = -1.0 / h;  // Vulkan: clip y points down
    m.proj[2][2] = 1.0 / (far - n);
    m.proj[3][2] = far / (far - n);
    m.proj[3][3] = 1.0;
    m.viewProj = m.proj * m.view;
    return m;
  }
  const double f = 1.0 / std::tan(0.5 * double(v.yfovRadians));
  m.proj[0][0] = f / aspect;
  m.proj[1][1] = -f;               // Vulkan: clip y points down
  m.proj[2][3] = -1.0;             // w = -z_view
  m.proj[3][2] = double(v.znear);  // z_ndc = near / -z_view: 1 at the near plane, 0 at infinity
  m.viewProj = m.proj * m.view;
  return m;
}

glm::dmat4 previousViewProjRelative(const View& previous, const glm::dvec3& currentPosition, double aspect) {
  CameraMatrices prev = cameraMatrices(previous, aspect);
  return prev.viewProj * glm::translate(glm::dmat4(1.0), currentPosition - previous.position);
}

SunShadowFit fitSunShadow(const View& view, double aspect, const scene::Bounds& sceneBounds,
                          const glm::dvec3& sunTravel, uint32_t mapSize) {
  const glm::dvec3 d = glm::normalize(sunTravel);
  const bool haveScene = sceneBounds.valid();
  const glm::dvec3 sceneCenter = haveScene ? sceneBounds.center() - view.position : glm::dvec3(0.0);
  const double sceneRadius = haveScene ? std::max(1e-30, 0.5 * glm::length(sceneBounds.size())) : 10.0;

  // Bounding sphere of the frustum slice [near, far], far = the scene's diameter.
  const double farDist = 2.0 * sceneRadius + glm::length(sceneCenter);
  const double ty = std::tan(0.5 * double(view.yfovRadians)), tx = ty * aspect;
  const glm::dvec3 f = view.forward;
  const glm::dvec3 r = glm::normalize(glm::cross(f, view.up));
  const glm::dvec3 u = glm::cross(r, f);
  std::array<glm::dvec3, 8> corners;
  int k = 0;
  // An orthographic view is a box: the same half-size at every distance.
  const double halfY = double(view.orthoHalfHeight), halfX = halfY * aspect;
  for (double dist : {double(view.znear), view.orthographic ? std::min(farDist, double(view.zfar)) : farDist})
    for (double sx : {-1.0, 1.0})
      for (double sy : {-1.0, 1.0})
        corners[k++] = view.orthographic ? f * dist + r * (sx * halfX) + u * (sy * halfY)
                                         : f * dist + r * (sx * tx * dist) + u * (sy * ty * dist);
  glm::dvec3 frustumCenter(0.0);
  for (auto& c : corners) frustumCenter += c / 8.0;
  double frustumRadius = 0.0;
  for (auto& c : corners) frustumRadius = std::max(frustumRadius, glm::length(c - frustumCenter));

  glm::dvec3 center = frustumRadius < sceneRadius ? frustumCenter : sceneCenter;
  double radius = std::min(frustumRadius, sceneRadius);

  const glm::dvec3 up = std::abs(d.y) < 0.99 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
  glm::dmat4 lightView = glm::lookAtRH(glm::dvec3(0.0), d, up);

  // Snap the window's centre to whole texels in light space.
  const double texel = 2.0 * radius / double(mapSize);
  glm::dvec3 lc = glm::dvec3(lightView * glm::dvec4(center, 1.0));
  lc.x = std::floor(lc.x / texel) * texel;
  lc.y = std::floor(lc.y / texel) * texel;

  // Depth range along the light: every corner of the scene's bounds, so off-screen casters
  // between the sun and the view still write depth.
  double zMin = 1e300, zMax = -1e300;
  auto extendZ = [&](const glm::dvec3& p) {
    double z = -(lightView * glm::dvec4(p, 1.0)).z;  // distance along the light's travel
    zMin = std::min(zMin, z);
    zMax = std::max(zMax, z);
  };
  if (haveScene) {
    for (int i = 0; i < 8; ++i) extendZ(sceneBounds.corner(i) - view.position);
  }
  extendZ(center + d * radius);
  extendZ(center - d * radius);
  const double pad = 0.01 * (zMax - zMin) + 1e-6 * sceneRadius;
  zMin -= pad;
  zMax += pad;

  glm::dmat4 proj = glm::orthoRH_ZO(lc.x - radius, lc.x + radius, lc.y - radius, lc.y + radius, zMin, zMax);
  SunShadowFit fit;
  fit.viewProj = proj * lightView;
  fit.texelWorld = texel;
  fit.radius = radius;
  fit.depthRange = zMax - zMin;
  return fit;
}

bool isCameraCut(const View& previous, const View& current, double sceneScale) {
  return lighting::cameraJumped(previous.position, previous.forward, current.position, current.forward, sceneScale);
}

}  // namespace tl::session
