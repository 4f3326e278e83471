// How a captured image is stored so that other tools (oiiotool, Nuke, Python) read it right,
// and how the viewer gets the frame's texels back from it. One table of encodings, both
// directions:
//   linear          float data as the frame held it (EXR half where exact, else float)
//   srgb-decoded    8-bit sRGB colour decoded to linear values (EXR half)
//   display         display-referred (tonemapped, sRGB-encoded) images: 8-bit PNG as shown
//   view-depth      reversed-Z depth as view depth in metres (EXR float, channel Z; inf where
//                   nothing was drawn), using the camera's near plane
//   normal          octahedral normals decoded to unit vectors (EXR float, N.x N.y N.z)
//   uint            integer images as exact 32-bit unsigned integers (EXR uint)
// Channel names are the resource's declared ones (graph::ResourceDesc::channels, e.g.
// motion.u motion.v, id), else R, G, B, A (Y for one channel).
#pragma once

#include "graph/executor.h"

#include <string>
#include <vector>

namespace tl::session {

struct StoredImage {
  std::string encoding;               // one of the names above
  std::string fileExtension;          // ".exr" or ".png"
  std::vector<std::string> channels;  // names, in file order
  uint32_t width = 0, height = 0;     // height: rows of all z slices
  bool half = false;                  // EXR: half rather than float
  std::vector<float> values;          // float encodings
  std::vector<uint32_t> integers;     // uint
  std::string meaning;                // one line for the manifest: what the numbers are
};

// The stored form of one read-back image. `znear`: the camera's near plane (view-depth).
StoredImage encodeCaptureImage(const graph::ResourceDesc& desc, const graph::Readback& image, float znear);

// The texels the frame held, as 32-bit floats (or exact integers) with `channels` per texel,
// from an image stored with `encoding` (`storedChannels` per texel). `formatName` is the
// original format's (gpu::FormatInfo::name), which says how precisely to restore normals.
// Throws SessionError for an unknown encoding.
std::vector<float> decodeCaptureValues(const std::string& encoding, const std::string& formatName,
                                       const std::vector<float>& stored, uint32_t storedChannels, uint32_t channels,
                                       float znear);

}  // namespace tl::session
