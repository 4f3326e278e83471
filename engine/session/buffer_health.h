// Radiance that cannot go wrong silently: after a frame read back with requestAllBuffers(),
// count per buffer the values that are not finite, and the values that are negative where
// nothing may be (radiance, irradiance, emission, AO, accumulations). An SH irradiance buffer
// (decoder `sh-irradiance`, luma SH + chroma) counts the pixels whose mean colour -- L0 and
// its chroma, converted to RGB -- has a channel below zero beyond half-float rounding: a
// colour no light can have, which resolves to negative radiance. Used by the GPU tests on
// hard cases and by `twinlight doctor`.
#pragma once

#include "session/session.h"

#include <cstdint>
#include <string>
#include <vector>

namespace tl::session {

struct BufferHealth {
  std::string name;
  std::string check;         // "finite", "finite, >= 0" or "finite, valid SH colour"
  uint64_t values = 0;       // values (or SH pixels) examined
  uint64_t nonFinite = 0;
  uint64_t negative = 0;     // below zero (or invalid SH colours)
  double mostNegative = 0.0; // the lowest such value (the RGB channel for SH)
  bool healthy() const { return nonFinite == 0 && negative == 0; }
};

// Whether resource `name` (described as `description`) holds a quantity that is never
// negative. Signed data -- normals, motion, chroma, SH coefficients, differences, depth codes --
// is checked for finiteness only.
bool holdsNonNegativeValues(const std::string& name, const std::string& description);

// Every float buffer the last frame read back, in the order of session.resources().
std::vector<BufferHealth> bufferHealth(const Session& session);

}  // namespace tl::session
