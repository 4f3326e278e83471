// Captures: one file per resource the graph lists, a manifest that round-trips, and values
// that read back from the files exactly as the frame held them.
#include "gpu_fixture.h"

#include "lighting/common/composite_pass.h"
#include "session/capture.h"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstring>
#include <fstream>

namespace tl::test {
namespace {

namespace fs = std::filesystem;

TEST_F(GpuTest, CaptureWritesEveryResourceAndReadsBackExactly) {
  auto& s = session();
  if (!s.device().rayTracing().pipeline) GTEST_SKIP() << s.device().rayTracing().unavailableReason;
  s.loadScene(contentFile("atrium.gltf"));
  s.setPath("rt");
  s.setSize(48, 27);
  const fs::path dir = fs::temp_directory_path() / "twinlight-capture-test";
  fs::remove_all(dir);
  nlohmann::json manifest = session::captureFrame(s, dir, 2);
  s.setPath("direct");

  // The manifest on disk is the one returned, and lists every resource of the graph.
  nlohmann::json onDisk = nlohmann::json::parse(std::ifstream(dir / "manifest.json"));
  EXPECT_EQ(onDisk, manifest);
  EXPECT_EQ(manifest["lightingPath"], "rt");
  EXPECT_EQ(manifest["resources"].size(), s.resources().size());
  size_t files = 0;
  for (const auto& r : manifest["resources"]) {
    if (r["file"].is_null()) {
      EXPECT_TRUE(r["imported"].get<bool>()) << r["name"] << ": only imported scene data is left out";
      continue;
    }
    ++files;
    EXPECT_TRUE(fs::exists(dir / r["file"].get<std::string>())) << r["file"];
  }
  EXPECT_GE(files, 20u);
  EXPECT_EQ(size_t(std::distance(fs::directory_iterator(dir), fs::directory_iterator())), files + 1);

  // Integer records are lossless; half-float buffers come back bit for bit as floats.
  auto hits = session::readCaptureImage(dir / "rt.hits.exr");
  const auto& rb = s.buffer("rt.hits");
  ASSERT_TRUE(hits.integer);
  ASSERT_EQ(hits.integers.size() * 4, rb.bytes.size());
  EXPECT_EQ(std::memcmp(hits.integers.data(), rb.bytes.data(), rb.bytes.size()), 0);
  auto shY = session::readCaptureImage(dir / "rt.gi.temporal.shY.exr");
  EXPECT_EQ(shY.values, s.buffer("rt.gi.temporal.shY").texels());
  // Depth as view depth in metres (near / reversed Z), float.
  auto depth = session::readCaptureImage(dir / "gbuffer.depth.exr");
  const std::vector<float> reversedZ = s.buffer("gbuffer.depth").texels();
  ASSERT_EQ(depth.values.size(), reversedZ.size());
  const float znear = s.view().znear;
  size_t drawn = 0;
  for (size_t i = 0; i < reversedZ.size(); ++i) {
    if (reversedZ[i] == 0.0f) {
      EXPECT_TRUE(std::isinf(depth.values[i])) << i;
      continue;
    }
    ++drawn;
    EXPECT_FLOAT_EQ(depth.values[i], znear / reversedZ[i]) << i;
  }
  EXPECT_GT(drawn, reversedZ.size() / 2);
}

}  // namespace
}  // namespace tl::test

namespace tl::test {
namespace {

// A capture reopened without its scene gives the viewer the values the frame had: integer
// images exactly, float images as stored, decoders and instance names from the manifest.
TEST_F(GpuTest, CaptureReopensWithoutTheSceneWithTheSameValues) {
  auto& s = session();
  s.loadScene(contentFile("cornell.gltf"));
  s.setPath("direct");
  s.setSize(40, 30);
  const fs::path dir = fs::temp_directory_path() / "twinlight-reopen-test";
  fs::remove_all(dir);
  session::captureFrame(s, dir, 1);
  const graph::Readback ids = s.buffer("gbuffer.instanceId"), normal = s.buffer("gbuffer.normal"),
                        depth = s.buffer("gbuffer.depth"), material = s.buffer("gbuffer.material");
  const graph::Readback live = s.buffer(lighting::kTonemapLdr);

  s.openCapture(dir);
  ASSERT_TRUE(s.hasCapture());
  const graph::Readback& ids2 = s.buffer("gbuffer.instanceId");
  ASSERT_EQ(ids2.bytes.size(), ids.bytes.size());
  EXPECT_EQ(ids2.bytes, ids.bytes) << "instance ids exact";
  EXPECT_EQ(s.buffer("gbuffer.normal").texels(), normal.texels())
      << "normals stored decoded (N.x N.y N.z) come back as the frame's octahedral snorm16 values";
  {
    // Stored as half: an 8-bit value such as the dielectric's F0 (sqrt 0.04 = 0.2) comes back
    // within half's precision (2^-11 relative), not bit for bit.
    const auto back = s.buffer("gbuffer.material").texels(), frame = material.texels();
    ASSERT_EQ(back.size(), frame.size());
    size_t worst = 0;
    for (size_t i = 0; i < back.size(); ++i)
      if (std::abs(back[i] - frame[i]) > std::abs(back[worst] - frame[worst])) worst = i;
    EXPECT_NEAR(back[worst], frame[worst], 1e-3f * std::max(1.0f, std::abs(frame[worst])))
        << "roughness metalness B A come back in that order (EXR sorts channels by name), texel value " << worst;
  }
  const graph::Readback depth2 = s.buffer("gbuffer.depth");
  ASSERT_EQ(depth2.texels().size(), depth.texels().size());
  for (size_t i = 0; i < depth.texels().size(); ++i)
    EXPECT_NEAR(depth2.texels()[i], depth.texels()[i], 1e-6f * depth.texels()[i]) << "reversed Z back from view depth";
  bool decoder = false;
  for (const auto& r : s.resources()) decoder |= r.name == "gbuffer.normal" && r.desc.decoder == "oct-normal";
  EXPECT_TRUE(decoder) << "decoders travel in the manifest";
  ASSERT_NE(s.decodingScene(), nullptr);
  EXPECT_EQ(s.decodingScene()->instances.size(), s.scene().instances.size());
  lighting::DisplayRequest show;
  show.source = "gbuffer.normal";
  s.setDisplay(show);
  s.renderFrames(1);  // the display pass over the captured image
  ASSERT_NE(s.displayImage(), nullptr);
  EXPECT_EQ(s.displayImage()->extent().width, 40u);
  s.setDisplay(std::nullopt);
  s.closeCapture();
  EXPECT_FALSE(s.hasCapture());

  // Closed, the scene renders again (the captured images it showed are gone: nothing may
  // still point at them) and gives the image it gave before the capture opened.
  s.renderFrames(1);
  const graph::Readback& again = s.buffer(lighting::kTonemapLdr);
  ASSERT_EQ(again.bytes.size(), live.bytes.size());
  size_t differ = 0;
  for (size_t i = 0; i < again.bytes.size(); ++i) differ += std::abs(int(again.bytes[i]) - int(live.bytes[i])) > 1;
  EXPECT_EQ(differ, 0u) << "the direct path renders the same view the same way";

  // A scene loaded while a capture is open replaces it the same way.
  s.openCapture(dir);
  s.setDisplay(show);
  s.renderFrames(1);
  s.setDisplay(std::nullopt);
  s.loadScene(contentFile("plane.gltf"));
  EXPECT_FALSE(s.hasCapture());
  s.renderFrames(1);
  EXPECT_EQ(s.buffer(lighting::kTonemapLdr).extent.width, 40u);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace tl::test

namespace tl::test {
namespace {

// What other tools read from a capture's files alone: colour decoded to linear (cornell's red
// wall is its albedo, 0.63 0.065 0.05, not the sRGB encoding 0.816 0.282 0.247), conventional
// channel names, the display image as PNG, ids with the manifest's table, the program's version
// and every setting in the manifest.
TEST_F(GpuTest, CaptureFilesAreLinearWithConventionalChannels) {
  auto& s = session();
  s.loadScene(contentFile("cornell.gltf"));
  s.setPath("direct");
  s.setSize(40, 30);
  const fs::path dir = fs::temp_directory_path() / "twinlight-capture-channels-test";
  fs::remove_all(dir);
  const nlohmann::json manifest = session::captureFrame(s, dir, 1);

  EXPECT_EQ(manifest["schema"], 2);
  EXPECT_TRUE(manifest["twinlight"]["version"].is_string());
  EXPECT_FALSE(manifest["twinlight"]["version"].get<std::string>().empty());
  EXPECT_EQ(manifest["settings"]["rtDenoise"], s.settings().rtDenoise) << "every setting, not a few";
  EXPECT_EQ(manifest["settings"]["width"], 40);
  auto channelsOf = [&](const std::string& resource) {
    auto in = OIIO::ImageInput::open((dir / resource).string());
    EXPECT_NE(in, nullptr) << resource;
    return in ? in->spec().channelnames : std::vector<std::string>{};
  };
  EXPECT_EQ(channelsOf("gbuffer.depth.exr"), (std::vector<std::string>{"Z"}));
  EXPECT_EQ(channelsOf("gbuffer.normal.exr"), (std::vector<std::string>{"N.x", "N.y", "N.z"}));
  EXPECT_EQ(channelsOf("gbuffer.motion.exr"), (std::vector<std::string>{"motion.u", "motion.v"}));
  EXPECT_EQ(channelsOf("gbuffer.instanceId.exr"), (std::vector<std::string>{"id"}));
  EXPECT_EQ(channelsOf("gbuffer.baseColor.exr"), (std::vector<std::string>{"R", "G", "B", "A"}));
  EXPECT_TRUE(fs::exists(dir / "tonemap.ldr.png")) << "the display image is a PNG";
  EXPECT_FALSE(fs::exists(dir / "tonemap.ldr.exr"));

  // Every pixel whose id names the red wall has its albedo in the base colour file.
  auto ids = session::readCaptureImage(dir / "gbuffer.instanceId.exr");
  auto base = session::readCaptureImage(dir / "gbuffer.baseColor.exr");
  uint32_t red = 0;
  for (const auto& e : manifest["instanceIds"])
    if (e["name"] == "left_wall_red") red = e["id"];
  ASSERT_NE(red, 0u);
  size_t wall = 0;
  for (size_t i = 0; i < ids.integers.size(); ++i) {
    if (ids.integers[i] != red) continue;
    ++wall;
    // 8-bit sRGB steps near 0.63 are 0.005 wide; 0.05 and 0.065 lie on finer ones.
    EXPECT_NEAR(base.values[i * 4 + 0], 0.63f, 0.004f) << i;
    EXPECT_NEAR(base.values[i * 4 + 1], 0.065f, 0.002f) << i;
    EXPECT_NEAR(base.values[i * 4 + 2], 0.05f, 0.002f) << i;
    EXPECT_EQ(base.values[i * 4 + 3], 1.0f) << "coverage";
  }
  EXPECT_GT(wall, 20u);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace tl::test
