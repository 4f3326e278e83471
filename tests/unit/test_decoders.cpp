// The buffer viewer's decoders invert the encoders the passes use.
#include "lighting/common/decoders.h"
#include "shared/albedo.h"
#include "shared/display.h"
#include "shared/packing.h"
#include "shared/rt.h"
#include "shared/sh.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

namespace tl::lighting {
namespace {

template <class T>
graph::Readback oneTexel(VkFormat format, const T& value) {
  graph::Readback r;
  r.format = format;
  r.extent = {1, 1, 1};
  r.bytes.resize(sizeof(T));
  std::memcpy(r.bytes.data(), &value, sizeof(T));
  return r;
}

// Appends the bytes of `v` (resize + memcpy: GCC 12 misreads vector::insert of raw bytes).
template <class T>
void appendBytes(std::vector<uint8_t>& bytes, const T& v) {
  const size_t at = bytes.size();
  bytes.resize(at + sizeof(T));
  std::memcpy(bytes.data() + at, &v, sizeof(T));
}

std::string find(const DecodedLines& lines, const std::string& label) {
  for (auto& [l, v] : lines)
    if (l == label) return v;
  return "(missing " + label + ")";
}

glm::vec3 parseVec(const std::string& text) {
  std::istringstream in(text);
  glm::vec3 v(NAN);
  in >> v.x >> v.y >> v.z;
  return v;
}

TEST(Decoders, SpecNamesTheDecoderAndItsCompanions) {
  DecoderSpec s = parseDecoderSpec("sh-irradiance coCg=rt.gi.temporal.coCgAo normal=gbuffer.normal");
  EXPECT_EQ(s.name, "sh-irradiance");
  EXPECT_EQ(s.companions.at("coCg"), "rt.gi.temporal.coCgAo");
  EXPECT_EQ(decoderCompanions("sh-irradiance coCg=a normal=b").size(), 2u);
  EXPECT_TRUE(decodeTexel("no-such-decoder", {oneTexel(VK_FORMAT_R32_UINT, 0u)}).empty());
}

TEST(Decoders, HitRecordRoundTrips) {
  const glm::vec3 albedo(0.5f, 0.25f, 0.75f);
  const uint32_t hit = shared::tlRtPackHit(3.5f, albedo);
  auto r = oneTexel(VK_FORMAT_R32_UINT, hit);
  DecodedLines lines = decodeTexel("rt-hit-record", {r});
  EXPECT_EQ(find(lines, "hit distance"), "3.5000 m");
  glm::vec3 a = parseVec(find(lines, "hit albedo"));
  EXPECT_NEAR(a.r, albedo.r, 0.02f);
  EXPECT_NEAR(a.g, albedo.g, 0.02f);
  EXPECT_NEAR(a.b, albedo.b, 0.02f);
  EXPECT_NE(find(decodeTexel("rt-hit-record", {oneTexel(VK_FORMAT_R32_UINT, shared::kRtHitMiss)}), "ray").find("miss"),
            std::string::npos);
  EXPECT_NE(find(rawTexel(r, 0, 0), "r").find(fmt::format("0x{:08x}", hit)), std::string::npos) << "raw bits shown";
}

// Integer texels narrower than 32 bits (the legacy rooms' r8ui, r16ui) show their values: they
// showed nothing when every channel was read as 4 bytes.
TEST(Decoders, NarrowIntegerTexelsShowTheirValues) {
  EXPECT_EQ(find(rawTexel(oneTexel(VK_FORMAT_R8_UINT, uint8_t(2)), 0, 0), "r"), "2 (0x02)");
  EXPECT_EQ(find(rawTexel(oneTexel(VK_FORMAT_R16_UINT, uint16_t(65535)), 0, 0), "r"), "65535 (0xffff)");
  EXPECT_EQ(find(rawTexel(oneTexel(VK_FORMAT_R32_UINT, uint32_t(7)), 0, 0), "r"), "7 (0x00000007)");
}

TEST(Decoders, HitSurfaceAndOctahedralNormalsRoundTrip) {
  const glm::vec3 n = glm::normalize(glm::vec3(0.3f, -0.8f, 0.52f));
  const glm::uvec2 surface(shared::tlOctEncodeSnorm16(n), shared::tlPackRgb9e5(glm::vec3(2.0f, 0.5f, 0.0f)));
  DecodedLines s = decodeTexel("rt-hit-surface", {oneTexel(VK_FORMAT_R32G32_UINT, surface)});
  glm::vec3 dn = parseVec(find(s, "hit normal")), e = parseVec(find(s, "hit emission"));
  EXPECT_LT(glm::length(dn - n), 1e-3f);
  EXPECT_NEAR(e.r, 2.0f, 0.01f);
  EXPECT_NEAR(e.g, 0.5f, 0.01f);
  // R16G16_SNORM as the G-buffer stores it.
  const glm::vec2 oct = shared::tlOctEncode(n);
  const int16_t snorm[2] = {int16_t(std::lround(oct.x * 32767.0f)), int16_t(std::lround(oct.y * 32767.0f))};
  graph::Readback r;
  r.format = VK_FORMAT_R16G16_SNORM;
  r.extent = {1, 1, 1};
  r.bytes.resize(4);
  std::memcpy(r.bytes.data(), snorm, 4);
  EXPECT_LT(glm::length(parseVec(find(decodeTexel("oct-normal", {r}), "normal")) - n), 1e-3f);
}

TEST(Decoders, ShIrradianceUsesTheCompanionsAtTheSameRelativePosition) {
  // One radiance sample projected into SH; the decoder resolves it against the pixel normal.
  const glm::vec3 dir = glm::normalize(glm::vec3(0.2f, 1.0f, 0.1f)), n(0.0f, 1.0f, 0.0f);
  shared::ShLumaCoCg sh = shared::tlShProjectRadiance(dir, glm::vec3(1.0f, 0.5f, 0.25f));
  // The SH at 2x2, chroma and normals at 4x4 (a quarter-resolution cone buffer, say).
  graph::Readback shY;
  shY.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  shY.extent = {2, 2, 1};
  for (int i = 0; i < 4; ++i) appendBytes(shY.bytes, sh.shY);
  graph::Readback coCg, normal;
  coCg.format = normal.format = VK_FORMAT_R32G32_SFLOAT;
  coCg.extent = normal.extent = {4, 4, 1};
  const glm::vec2 octN = shared::tlOctEncode(n);
  for (int i = 0; i < 16; ++i) {
    appendBytes(coCg.bytes, sh.coCg);
    appendBytes(normal.bytes, octN);
  }
  DecodeInput in{shY, 1, 1, 0, [&](const std::string& name) -> const graph::Readback* {
                   return name == "chroma" ? &coCg : name == "normals" ? &normal : nullptr;
                 }};
  DecodedLines lines = decodeTexel("sh-irradiance coCg=chroma normal=normals", in);
  const glm::vec3 expected = shared::tlShResolveIrradiance(sh, n), got = parseVec(find(lines, "irradiance (at normal)"));
  EXPECT_NEAR(got.r, expected.r, 1e-3f);
  EXPECT_NEAR(got.g, expected.g, 1e-3f);
  EXPECT_NEAR(got.b, expected.b, 1e-3f);
  EXPECT_LT(glm::length(parseVec(find(lines, "dominant direction")) - dir), 0.01f);
}

TEST(Decoders, AmbientOcclusionIsTheVisibilityAndAGreyMeaning) {
  EXPECT_EQ(find(decodeTexel("ao", {oneTexel(VK_FORMAT_R32_SFLOAT, 0.25f)}), "visibility"), "0.250 (75% occluded)");
  const auto m = meaningView("ao");
  ASSERT_TRUE(m);
  EXPECT_EQ(m->quantity, "ambient occlusion");
  EXPECT_FALSE(m->fitted) << "visibility has its own fixed range, 0..1";
  EXPECT_TRUE(negativesInvalid("ao", VK_FORMAT_R16_SFLOAT));
}

TEST(Decoders, VoxelFacesNameTheFaceLevelAndVoxel) {
  // R = 2: six face blocks of 2 along x (12 wide), 2 levels of 2 along z (4 deep), RGBA32F.
  graph::Readback r;
  r.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  r.extent = {12, 2, 4};
  for (uint32_t z = 0; z < 4; ++z)
    for (uint32_t y = 0; y < 2; ++y)
      for (uint32_t x = 0; x < 12; ++x) appendBytes(r.bytes, glm::vec4(float(x), float(y), float(z), 0.5f));
  DecodedLines lines = decodeTexel("voxel-faces", {r, 5, 1, 3});
  EXPECT_EQ(find(lines, "face").substr(0, 2), "+y") << "x 5 is in block 2 of +x -x +y -y +z -z";
  EXPECT_EQ(find(lines, "voxel"), "level 1, x 1 y 1 z 1 of 2");
  EXPECT_EQ(parseVec(find(lines, "radiance")), glm::vec3(5.0f, 1.0f, 3.0f));
  EXPECT_EQ(find(lines, "opacity"), "0.500");
  EXPECT_EQ(find(decodeTexel("voxel-faces", {r, 11, 0, 0}), "face").substr(0, 2), "-z");
  // The slice index named: level and world z voxel; a plain 3D image says its axis.
  EXPECT_EQ(sliceMeaning("voxel-faces", {384, 64, 256}, 70), "level 1, world z voxel 6 of 64");
  EXPECT_EQ(sliceMeaning("voxel-faces", {384, 64, 64}, 500), "level 0, world z voxel 63 of 64") << "past the end: the last";
  EXPECT_EQ(sliceMeaning("", {8, 8, 10}, 5), "z 5 of 10");
}

TEST(Decoders, InstanceIdNamesTheInstance) {
  scene::Scene s;
  s.instances.resize(3);
  s.instances[2].name = "crate";
  DecodeInput in{oneTexel(VK_FORMAT_R32_UINT, 3u)};
  in.scene = &s;
  EXPECT_EQ(find(decodeTexel("instance-id", in), "instance"), "crate (index 2)");
  EXPECT_NE(find(decodeTexel("instance-id", {oneTexel(VK_FORMAT_R32_UINT, 0u)}), "instance").find("none"), std::string::npos);
}

TEST(Decoders, IbufferSumsSayWhatTheyWeigh) {
  auto r = oneTexel(VK_FORMAT_R32G32B32A32_SFLOAT, glm::vec4(1.0f, 2.0f, 3.0f, 0.0f));
  DecodedLines lines = decodeTexel("ibuffer-sg2", {r});
  EXPECT_EQ(parseVec(find(lines, "sum")), glm::vec3(1.0f, 2.0f, 3.0f));
  EXPECT_NE(find(lines, "weighs").find("Schlick"), std::string::npos);
  EXPECT_NE(find(decodeTexel("ibuffer-dg", {r}), "weighs").find("diffuse layer"), std::string::npos);
  EXPECT_NE(find(decodeTexel("ibuffer-ms", {r}), "weighs").find("multiple-scattering"), std::string::npos);
}

TEST(Decoders, DepthShareIsAShareOfTheWholeRadiance) {
  auto part = oneTexel(VK_FORMAT_R32G32B32A32_SFLOAT, glm::vec4(0.25f, 0.25f, 0.25f, 0.0f));
  auto whole = oneTexel(VK_FORMAT_R32G32B32A32_SFLOAT, glm::vec4(1.0f, 1.0f, 1.0f, 0.0f));
  DecodeInput in{part, 0, 0, 0, [&](const std::string& name) { return name == "all" ? &whole : nullptr; }};
  EXPECT_EQ(find(decodeTexel("depth-share whole=all", in), "share of the pixel"), "25.0%");
  EXPECT_EQ(find(decodeTexel("depth-share whole=missing", in), "share of the pixel"), "whole radiance not read back");
}

TEST(Decoders, AlbedoSourceNamesWhereTheAlbedoCameFrom) {
  auto r = oneTexel(VK_FORMAT_R32G32B32A32_SFLOAT, glm::vec4(0.5f, 0.5f, 0.5f, shared::kAlbedoSourceBaked));
  EXPECT_EQ(find(decodeTexel("albedo-source", {r}), "source"), "baked");
  EXPECT_FALSE(meaningView("albedo-source")) << "a colour reads as a colour";
}

TEST(Decoders, EachDecodersDefaultViewAndSign) {
  const auto hit = meaningView("rt-hit-record");
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->meaning, shared::kDisplayMeaningHitDistance);
  EXPECT_TRUE(hit->fitted && hit->falseColour);
  EXPECT_EQ(hit->unit, "m");
  ASSERT_TRUE(meaningView("oct-normal"));
  EXPECT_EQ(meaningView("oct-normal")->meaning, shared::kDisplayMeaningOctNormal);
  ASSERT_TRUE(meaningView("rt-hit-surface"));
  EXPECT_EQ(meaningView("rt-hit-surface")->meaning, shared::kDisplayMeaningHitNormal);
  const auto sh = meaningView("sh-irradiance coCg=c normal=n");
  ASSERT_TRUE(sh);
  EXPECT_EQ(sh->meaning, shared::kDisplayMeaningShIrradiance);
  EXPECT_EQ(sh->companions, (std::vector<std::string>{"c", "n"}));
  EXPECT_FALSE(meaningView("sh-irradiance coCg=c")) << "no normal to resolve it at";
  for (const char* none : {"instance-id", "voxel-faces", "ibuffer-dg", "depth-share whole=w", "no-such-decoder", ""})
    EXPECT_FALSE(meaningView(none)) << none;
  // Signed by nature: directions and SH; signed by format: SNORM; the rest must not go negative.
  for (const char* signedSpec : {"oct-normal", "sh-irradiance coCg=c normal=n", "rt-hit-surface"})
    EXPECT_FALSE(negativesInvalid(signedSpec, VK_FORMAT_R16G16_SFLOAT)) << signedSpec;
  EXPECT_FALSE(negativesInvalid("", VK_FORMAT_R16G16_SNORM));
  for (const char* unsignedSpec : {"", "ibuffer-dg", "depth-share", "albedo-source", "voxel-faces"})
    EXPECT_TRUE(negativesInvalid(unsignedSpec, VK_FORMAT_R16G16B16A16_SFLOAT)) << unsignedSpec;
}

TEST(Decoders, FittedMeaningsGiveAValuePerTexel) {
  graph::Readback hits;
  hits.format = VK_FORMAT_R32_UINT;
  hits.extent = {2, 1, 1};
  appendBytes(hits.bytes, shared::tlRtPackHit(2.0f, glm::vec3(0.5f)));
  appendBytes(hits.bytes, shared::kRtHitMiss);
  const std::vector<float> d = meaningValues("rt-hit-record", hits, nullptr);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_NEAR(d[0], 2.0f, 1e-3f);
  EXPECT_TRUE(std::isnan(d[1])) << "a miss has no distance";
  // SH irradiance: the largest channel at the normal; nothing without its companions.
  const glm::vec3 n(0.0f, 1.0f, 0.0f);
  const shared::ShLumaCoCg sh = shared::tlShProjectRadiance(n, glm::vec3(1.0f, 0.5f, 0.25f));
  auto shY = oneTexel(VK_FORMAT_R32G32B32A32_SFLOAT, sh.shY);
  auto coCg = oneTexel(VK_FORMAT_R32G32_SFLOAT, sh.coCg);
  auto normal = oneTexel(VK_FORMAT_R32G32_SFLOAT, shared::tlOctEncode(n));
  auto companion = [&](const std::string& name) { return name == "c" ? &coCg : name == "n" ? &normal : nullptr; };
  const std::vector<float> e = meaningValues("sh-irradiance coCg=c normal=n", shY, companion);
  ASSERT_EQ(e.size(), 1u);
  const glm::vec3 expected = shared::tlShResolveIrradiance(sh, n);
  EXPECT_NEAR(e[0], std::max({expected.r, expected.g, expected.b}), 1e-4f);
  EXPECT_TRUE(meaningValues("sh-irradiance coCg=c normal=gone", shY, companion).empty());
  EXPECT_TRUE(meaningValues("oct-normal", normal, nullptr).empty()) << "a direction is not fitted to a range";
}

}  // namespace
}  // namespace tl::lighting
