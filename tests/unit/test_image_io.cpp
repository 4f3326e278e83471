// EXR output: an image whose values all fit the half-float range is written in
// half floats; one with any value beyond 65504 is written in 32-bit floats, so nothing clips,
// and the write reports how many pixels would have clipped and how many are not finite. Under
// `--sun 1e6` 63-67% of the pixels used to clip silently at 65504.
#include "../common/temp_dir.h"
#include "session/image_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>

#include <unistd.h>

namespace tl::session {
namespace {

using tl::test::contentFile;
using tl::test::TempDir;

namespace fs = std::filesystem;


// A 2x2 RGBA32F read-back holding `rgba` (four texels).
graph::Readback rgba32f(const std::array<float, 16>& rgba) {
  graph::Readback image;
  image.name = "composite.hdr";
  image.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  image.extent = {2, 2, 1};
  image.bytes.resize(sizeof(rgba));
  std::memcpy(image.bytes.data(), rgba.data(), sizeof(rgba));
  return image;
}

TEST(ExrOutput, ValuesBeyondHalfRangeAreWrittenAsFloat32AndCounted) {
  TempDir dir;
  const fs::path file = dir.path / "sun.exr";
  // Two pixels beyond 65504 (one in a single channel), one with 1.0001 (half would round it
  // to 1), one ordinary.
  const auto report = writeImageAtomically(file, rgba32f({1e6f, 2.5e5f, 7e4f, 1, 70000.0f, 1, 1, 1, 1.0001f, 0.5f, 0.25f, 1,
                                                          0.1f, 0.2f, 0.3f, 1}),
                                           ImageEncoding::Linear);
  EXPECT_EQ(report.pixels, 4u);
  EXPECT_EQ(report.beyondHalf, 2u);
  EXPECT_EQ(report.nonFinite, 0u);
  EXPECT_TRUE(report.float32);
  const auto back = readExrRgb(file);
  ASSERT_TRUE(back);
  ASSERT_EQ(back->rgb.size(), 12u);
  EXPECT_EQ(back->rgb[0], 1e6f);  // 65504 in a half file
  EXPECT_EQ(back->rgb[1], 2.5e5f);
  EXPECT_EQ(back->rgb[3], 70000.0f);
  EXPECT_EQ(back->rgb[6], 1.0001f);  // float32 keeps what half would round to 1
}

TEST(ExrOutput, ValuesWithinHalfRangeStayHalf) {
  TempDir dir;
  const fs::path file = dir.path / "room.exr";
  const auto report = writeImageAtomically(file, rgba32f({65504.0f, 60000.0f, 1, 1, 1.0001f, 0.5f, 0.25f, 1, 0, 0, 0, 1,
                                                          2, 3, 4, 1}),
                                           ImageEncoding::Linear);
  EXPECT_EQ(report.beyondHalf, 0u);
  EXPECT_FALSE(report.float32);
  const auto back = readExrRgb(file);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->rgb[0], 65504.0f);  // the largest half: kept
  EXPECT_EQ(back->rgb[1], 60000.0f);
  EXPECT_EQ(back->rgb[3], 1.0f);      // half precision: 1.0001 rounds to 1
}

TEST(ExrOutput, NonFinitePixelsAreCounted) {
  TempDir dir;
  const float inf = std::numeric_limits<float>::infinity();
  const auto report = writeImageAtomically(
      dir.path / "bad.exr", rgba32f({std::nanf(""), 0, 0, 1, 0, inf, 0, 1, 0, 0, -inf, 1, 1, 1, 1, 1}), ImageEncoding::Linear);
  EXPECT_EQ(report.nonFinite, 3u);
  EXPECT_EQ(report.beyondHalf, 0u);  // infinity is not counted as a value that would clip
}

}  // namespace
}  // namespace tl::session
