// Camera and sun-shadow matrices, in double precision and in camera-relative space (the
// camera at the origin), so a scene 10^6 m from the world origin renders like one at it.
// Pure functions: unit-tested without a GPU.
#pragma once

#include "scene/scene.h"
#include "session/session.h"

namespace tl::session {

struct CameraMatrices {
  glm::dmat4 view;      // rotation only
  glm::dmat4 proj;      // infinite reversed-Z, Vulkan clip space (y down, z in [0,1])
  glm::dmat4 viewProj;
};

CameraMatrices cameraMatrices(const View& view, double aspect);

// A camera cut: between two frames the camera jumped more than a fifth of the scene's size or
// turned by more than 60 degrees (lighting::cameraJumped). No motion vectors span it; the
// histories that reproject see it in the frame key (FramePart::CameraCut) and restart.
bool isCameraCut(const View& previous, const View& current, double sceneScale);

// The previous frame's view-projection, applied to points relative to *this* frame's
// camera position (so motion vectors need no absolute positions).
glm::dmat4 previousViewProjRelative(const View& previous, const glm::dvec3& currentPosition, double aspect);

struct SunShadowFit {
  glm::dmat4 viewProj;     // camera-relative world -> shadow clip (x,y in [-1,1], z in [0,1])
  double texelWorld = 0;   // world size of one shadow-map texel
  double radius = 0;       // half-extent of the orthographic window
  double depthRange = 0;   // metres covered by the map's depth range [0, 1]
};

// Fits an orthographic sun view to what the camera sees: the smaller of the bounding
// sphere of the view frustum (out to the scene's size) and the scene's bounding sphere,
// snapped to whole texels so the map does not shimmer as the camera moves; its depth range
// covers the whole scene so casters outside the view still cast.
SunShadowFit fitSunShadow(const View& view, double aspect, const scene::Bounds& sceneBounds,
                          const glm::dvec3& sunTravel, uint32_t mapSize);

}  // namespace tl::session
