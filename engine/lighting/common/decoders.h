// Texel decoders for the buffer viewer's pixel probe. A resource that needs decoding to be
// understood says so in its description (graph::ResourceDesc::decoder, set where it is
// written): "NAME key=resource ...". The viewer asks the decoders, by that spec, what a texel
// means; it never knows a resource by name. Each decoder is one row of the table in
// decoders.cpp (its decoding, default view, sign and slices). The decoders (and what their
// companions are):
//   rt-hit-record          r32ui hit record: distance + albedo, or miss / pending (shared/rt.h)
//   rt-hit-surface         rg32ui: hit normal (oct snorm16) + emission (rgb9e5)
//   oct-normal             rg16 snorm octahedral normal (shared/packing.h)
//   instance-id            r32ui instance index + 1: the scene instance's name
//   sh-irradiance          rgba16f L1 SH of luma; coCg=RESOURCE (chroma in its xy) normal=RESOURCE
//                          (oct normal): irradiance in the pixel's normal direction, and the SH's
//                          dominant direction and directionality
//   albedo-source          rgba16f per-instance albedo, source code in alpha (shared/albedo.h)
//   ibuffer-dg, -sg1,      rgba32f sums of light of redeferred shading's I-buffer (shared/redeferred.h):
//   -sg2, -ms              the sum, its luminance and what it weighs
//   depth-share            rgba32f radiance of one group of path depths (reference.bounce*);
//                          whole=RESOURCE (the pixel's whole radiance): the group's share of it
//   ao                     ambient occlusion: visibility in r (1 open, 0 fully occluded)
//   voxel-faces            3D rgba16f anisotropic voxels (shared/legacy.h): six face blocks of
//                          R^3 along x (R = the height), levels of R stacked in z (world axes)
#pragma once

#include "graph/executor.h"
#include "scene/scene.h"

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace tl::lighting {

inline constexpr const char* kDepthShareDecoder = "depth-share";
inline constexpr const char* kIbufferDecoderPrefix = "ibuffer-";  // + dg, sg1, sg2, ms

// The spec of an L1 SH luma image whose chroma is in `coCg`, read in the G-buffer's normal
// direction (both the rt and the legacy path write such pairs).
inline std::string shIrradianceDecoder(std::string_view coCg) {
  return "sh-irradiance coCg=" + std::string(coCg) + " normal=gbuffer.normal";
}

struct DecoderSpec {
  std::string name;
  std::map<std::string, std::string> companions;  // role -> resource name
};
DecoderSpec parseDecoderSpec(const std::string& spec);

// What a decoder may look at: the texel's resource read back, the texel, other resources of
// the same frame (companions, by name; null when not read back) and the scene.
struct DecodeInput {
  const graph::Readback& resource;
  uint32_t x = 0, y = 0, z = 0;
  std::function<const graph::Readback*(const std::string&)> companion;
  const scene::Scene* scene = nullptr;
};

using DecodedLines = std::vector<std::pair<std::string, std::string>>;  // label, value

// Raw stored values of one texel: integers as integers (and hex), floats as floats.
DecodedLines rawTexel(const graph::Readback& resource, uint32_t x, uint32_t y, uint32_t z = 0);
// Empty when the spec names no known decoder. Companions are sampled at the same relative
// position when their size differs (quarter-resolution cones against a full-size normal).
DecodedLines decodeTexel(const std::string& spec, const DecodeInput& input);
// The resources a spec needs read back beside its own.
std::vector<std::string> decoderCompanions(const std::string& spec);

// What a decoded resource means, as the viewer shows it by default (its stored values stay
// one click away): the quantity, its unit, how to read the colours, and how the display
// maps it (shared/display.h kDisplayMeaning*).
struct MeaningView {
  uint32_t meaning = 0;                 // kDisplayMeaning*
  std::string quantity;                 // "hit distance", "shading normal", ...
  std::string unit;                     // "m"; empty for a direction
  std::string legend;                   // how to read the colours
  bool fitted = false;                  // over a range fitted to meaningValues (else fixed colours)
  bool falseColour = false;             // a scalar through the false-colour ramp (its legend)
  std::vector<std::string> companions;  // the display's companions A, B, by name
};
// None for a decoder whose stored values already read as what they mean (instance ids are
// a colour per instance, per-instance albedo is a colour) or an unknown spec.
std::optional<MeaningView> meaningView(const std::string& spec);
// The meaning's value per texel of slice 0, row by row (a scalar: hit distance in metres,
// irradiance luminance), NaN where there is none (a miss); for the range fit and the
// histogram. Empty when the meaning is not fitted or a companion was not read back.
std::vector<float> meaningValues(const std::string& spec, const graph::Readback& resource,
                                 const std::function<const graph::Readback*(const std::string&)>& companion);
// Whether a negative stored value is invalid in such a resource, so the viewer flags it:
// not for directions (octahedral normals, SNORM data) nor SH coefficients, whose L1 terms
// are signed; yes for radiance, irradiance, colours and the rest.
bool negativesInvalid(const std::string& spec, VkFormat format);

// What a 3D resource's slice index is, by its decoder ("level 1, world z voxel 5 of 64"), or
// the plain axis ("z 37 of 192") when the decoder does not say.
std::string sliceMeaning(const std::string& spec, const VkExtent3D& extent, uint32_t slice);

}  // namespace tl::lighting
