// The pixel one invocation of an illumination pass in I-buffer form shades (shared/
// redeferred.h kIbufferStage*): its own at full rate, the pattern's n-th pixel when the pattern
// is dispatched densely (redeferredRate 1/2, 1/4), or its own again in the refining run only if
// ibuffer.upsample left it to be shaded. ivec2(-1): none. The includer declares `frame` and
//   layout(binding = kIbufferRefineMaskSampled) uniform sampler2D refineMask;
ivec2 ibufferStagePixel(uint stage, uint pattern) {
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  ivec2 p = stage == kIbufferStagePattern ? tlIbufferPatternPixel(g, pattern) : g;
  if (any(greaterThanEqual(p, ivec2(frame.viewport.xy)))) return ivec2(-1);
  if (stage == kIbufferStageRefine && texelFetch(refineMask, p, 0).r != kIbufferRefined) return ivec2(-1);
  return p;
}
