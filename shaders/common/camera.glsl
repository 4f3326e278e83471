// Camera-relative positions and distances from the G-buffer depth, shared by every pass that
// reconstructs them. The includer declares `frame` (FrameConstants).
//   cameraRelativePosition(uv, depth)  point under a screen uv at a reversed-Z depth
//   pixelPosition(p, depth)             the same at the centre of pixel p
//   viewW(position)                     distance along the view axis (clip w)
//   depthToViewW(depth)                 the same straight from depth: depth = near / w
//   pixelFootprint(w)                   world size of one pixel at view distance w

vec3 cameraRelativePosition(vec2 uv, float depth) {
  vec4 p = frame.invViewProj * vec4(uv * 2.0 - 1.0, depth, 1.0);
  return p.xyz / p.w;
}
vec3 pixelPosition(ivec2 p, float depth) { return cameraRelativePosition((vec2(p) + 0.5) * frame.viewport.zw, depth); }
float viewW(vec3 position) { return (frame.viewProj * vec4(position, 1.0)).w; }
float depthToViewW(float depth) { return frame.proj[3][2] / depth; }
float pixelFootprint(float w) { return 2.0 * w / (abs(frame.proj[1][1]) * frame.viewport.y); }
