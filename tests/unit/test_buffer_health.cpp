// Which buffers the doctor requires to be non-negative (session/buffer_health.h): radiance,
// irradiance, AO and visibility must not go below zero; signed quantities (SH, chroma,
// normals, motion, differences, directions) may.
#include "session/buffer_health.h"

#include <gtest/gtest.h>

namespace tl::session {
namespace {

TEST(BufferHealth, RadianceAndVisibilityMustNotBeNegative) {
  EXPECT_TRUE(holdsNonNegativeValues("composite.hdr", "scene-linear radiance"));
  EXPECT_TRUE(holdsNonNegativeValues("legacy.ao", "ambient occlusion"));
  EXPECT_TRUE(holdsNonNegativeValues("rt.shadow", "sun visibility"));
}

TEST(BufferHealth, SignedQuantitiesMayBeNegative) {
  EXPECT_FALSE(holdsNonNegativeValues("rt.gi.shY", "irradiance as SH"));
  EXPECT_FALSE(holdsNonNegativeValues("gbuffer.normal", "octahedral normal"));
  EXPECT_FALSE(holdsNonNegativeValues("gbuffer.motion", "screen motion"));
  // A direction beside a visibility (the bentsky plugin's history): the direction decides.
  EXPECT_FALSE(holdsNonNegativeValues("bentsky.history", "mean escaping direction (xyz) and visibility (w), last frame"));
}

}  // namespace
}  // namespace tl::session
