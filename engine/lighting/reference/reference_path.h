// What the reference path tracer is made of, for those who must know when it changed: the
// compare command's on-disk reference cache keys its images by a hash of these shaders' SPIR-V.
#pragma once

#include "graph/resource_name.h"

#include <string>
#include <vector>

namespace tl::lighting {

// The reference's noise, as graph resources every reference frame makes: the standard error
// of each pixel's estimate (rgba32f: rgb per channel, a the pixel's samples) and its sum over
// the image (a buffer of one shared::RefNoiseTotals, read back every frame:
// shared::tlRefRelativeStdError gives the image's relative standard error).
inline constexpr graph::ImageName kReferenceStdErr{"reference.stderr"};
inline constexpr graph::BufferName kReferenceNoise{"reference.noise"};
// Where each frame's samples went (adaptive sampling, shared/reference.h): rgba32f, the pixel's
// samples this frame (x), the first one's number (y), the standard deviation the next frame
// allocates by (z).
inline constexpr graph::ImageName kReferenceAllocation{"reference.allocation"};
// The benchmark's trivial kernel (referenceRawRayProbe): rays traced per pixel (r32f).
inline constexpr graph::ImageName kReferenceRawRays{"reference.rawRays"};

// The shaders (relative to the shader folder, as gpu::loadSpirv takes them) of every
// pipeline the reference path builds.
std::vector<std::string> referenceShaders();

// The reference's radiance split by path depth, the scattering events between the light and
// the camera (what --bounces caps), as on-demand graph resources (rgba32f, the image's size):
// [0] depths 0 and 1 (emission and direct light), [1] depth 2 (the first bounce), [2] depth 3
// (the second bounce), [3] depth 4 and more. Over the same frames they sum to
// reference.radiance; the sum of the first k is the reference rendered with --bounces k.
const std::vector<std::string>& referenceBounceBuffers();
// The same radiance split by the lobe of the first surface the camera sees that reflected it:
// [0] its diffuse layer, [1] its specular lobes (highlights and reflections). What the camera
// sees directly (emission, the sky) is in neither. Computed by the same pass and frames.
const std::vector<std::string>& referenceLobeBuffers();

}  // namespace tl::lighting
