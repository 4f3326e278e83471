// Hard numerical cases through every lighting path: surfaces emitting 1e4 to 1e7,
// a sun of 1e6. Every float buffer the frame writes is read back and counted
// (session/buffer_health.h): no value may be non-finite, no radiance, irradiance, emission or
// AO negative, and no SH irradiance may store a colour with a negative channel. Before the
// fix the rt path's SH saturated channel by channel in half floats next to such emitters and
// resolved to negative irradiance (composite.irradiance down to -4,596 on cornell at 1e5).
#include "gpu_fixture.h"
#include "session/buffer_health.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <fstream>

#include <unistd.h>

namespace tl::test {
namespace {

namespace fs = std::filesystem;

class HardCases : public GpuTest {
 protected:
  void SetUp() override {
    GpuTest::SetUp();
    dir_ = fs::temp_directory_path() / fmt::format("twinlight-hard-{}", ::getpid());
    fs::create_directories(dir_);
    fs::copy_file(contentFile("cornell.bin"), dir_ / "cornell.bin", fs::copy_options::overwrite_existing);
  }
  void TearDown() override {
    session().setPath("direct");
    session().settings() = lighting::RenderSettings{};
    fs::remove_all(dir_);
    GpuTest::TearDown();
  }

  // Cornell with the named materials emitting white light of `strength`.
  fs::path emittingCornell(const std::vector<std::string>& materials, double strength) {
    auto j = nlohmann::json::parse(std::ifstream(contentFile("cornell.gltf")));
    for (auto& m : j["materials"])
      if (std::find(materials.begin(), materials.end(), m["name"].get<std::string>()) != materials.end()) {
        m["emissiveFactor"] = {1.0, 1.0, 1.0};
        m["extensions"] = {{"KHR_materials_emissive_strength", {{"emissiveStrength", strength}}}};
      }
    const fs::path file = dir_ / fmt::format("cornell_{:g}.gltf", strength);
    std::ofstream(file) << j.dump();
    return file;
  }

  // Renders `frames` frames of every available path and expects every buffer healthy.
  void expectHealthyInEveryPath(const std::string& what, uint32_t frames) {
    for (const auto& path : session().paths()) {
      if (!path.available) continue;
      SCOPED_TRACE(what + ", " + path.name);
      session().setPath(path.name);
      session().settings().referenceSamplesPerFrame = 4;
      session().resetHistory();
      session().requestAllBuffers();
      session().renderFrames(frames);
      size_t checked = 0;
      for (const auto& h : session::bufferHealth(session())) {
        ++checked;
        EXPECT_TRUE(h.healthy()) << h.name << " (" << h.check << "): " << h.nonFinite << " non-finite, " << h.negative
                                 << " negative of " << h.values << ", lowest " << h.mostNegative;
      }
      EXPECT_GT(checked, 5u) << "the frame read back too few buffers to check";
    }
  }

  fs::path dir_;
};

TEST_F(HardCases, WallsEmitting1e5) {
  session().loadScene(emittingCornell({"cornell_white", "cornell_red", "cornell_green"}, 1e5));
  session().setSize(64, 64);
  expectHealthyInEveryPath("walls at 1e5", 6);
}

TEST_F(HardCases, LightEmitting1e7) {
  session().loadScene(emittingCornell({"ceiling_light"}, 1e7));
  session().setSize(48, 48);
  expectHealthyInEveryPath("ceiling light at 1e7", 4);
}

TEST_F(HardCases, SunOf1e6) {
  session().loadScene(contentFile("atrium.gltf"));
  session().setSize(64, 36);
  auto light = session().lighting();
  light.sunIrradiance = glm::vec3(1e6f);
  session().setLighting(light);
  expectHealthyInEveryPath("sun at 1e6", 3);
}

}  // namespace
}  // namespace tl::test
