// A tileable blue-noise mask made by void-and-cluster (Ulichney 1993): each texel holds its
// rank in 0..size*size-1, and any threshold of the ranks gives points spread evenly with
// no low-frequency clumps. The RT path's rays take their two uniforms from two such masks.
#pragma once

#include <cstdint>
#include <vector>

namespace tl::lighting {

// size x size ranks, row-major; deterministic for a seed on every machine.
std::vector<uint16_t> voidAndClusterRanks(uint32_t size, uint32_t seed);

}  // namespace tl::lighting
