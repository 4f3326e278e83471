// Camera-relative positions and distances from the G-buffer depth, shared by every pass that
// reconstructs them, for the perspective and the orthographic camera (frame.cameraAxis.w). The
// includer declares `frame` (FrameConstants).
//   cameraRelativePosition(uv, depth)  point under a screen uv at a reversed-Z depth
//   pixelPosition(p, depth)             the same at the centre of pixel p
//   viewW(position)                     distance along the view axis (perspective: clip w)
//   depthToViewW(depth)                 the same straight from depth (perspective: depth = near / w;
//                                       orthographic: linear from 1 at the near plane to 0 at the far)
//   pixelFootprint(w)                   world size of one pixel at view distance w
//   viewWOfClip(clip)                   viewW of a point in (this or last frame's) clip space
//   towardsViewer(position)             unit direction from a point to the eye (orthographic: -axis)
//   cameraRay(ndc)                      the primary ray through a point of the image

#ifndef TL_CAMERA_GLSL
#define TL_CAMERA_GLSL
bool cameraOrthographic() { return frame.cameraAxis.w != 0.0; }
vec3 cameraRelativePosition(vec2 uv, float depth) {
  vec4 p = frame.invViewProj * vec4(uv * 2.0 - 1.0, depth, 1.0);
  return p.xyz / p.w;
}
vec3 pixelPosition(ivec2 p, float depth) { return cameraRelativePosition((vec2(p) + 0.5) * frame.viewport.zw, depth); }
float viewW(vec3 position) {
  return cameraOrthographic() ? dot(position, frame.cameraAxis.xyz) : (frame.viewProj * vec4(position, 1.0)).w;
}
float depthToViewW(float depth) {
  return cameraOrthographic() ? (frame.proj[3][2] - depth) / frame.proj[2][2] : frame.proj[3][2] / depth;
}
float pixelFootprint(float w) {
  return 2.0 * (cameraOrthographic() ? 1.0 : w) / (abs(frame.proj[1][1]) * frame.viewport.y);
}
// The distance along the view axis of a point given in clip space by viewProj or prevViewProj
// (the projection is the same): clip w for a perspective, from z for an orthographic camera.
float viewWOfClip(vec4 clip) { return cameraOrthographic() ? (frame.proj[3][2] - clip.z) / frame.proj[2][2] : clip.w; }
vec3 towardsViewer(vec3 position) { return cameraOrthographic() ? -frame.cameraAxis.xyz : normalize(-position); }

// A perspective camera's rays leave the eye (the origin of camera-relative space); an
// orthographic camera's leave its near plane, all along the view axis.
struct CameraRay {
  vec3 origin;
  vec3 direction;
};
CameraRay cameraRay(vec2 ndc) {
  vec4 onNear = frame.invViewProj * vec4(ndc, 1.0, 1.0);  // reversed Z: 1 is the near plane
  vec3 p = onNear.xyz / onNear.w;
  return cameraOrthographic() ? CameraRay(p, frame.cameraAxis.xyz) : CameraRay(vec3(0.0), normalize(p));
}
#endif
