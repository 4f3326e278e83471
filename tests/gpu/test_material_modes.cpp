// Material override modes (RenderSettings::materials, shared/material_mode.h) in every path and
// the reference:
//   - clay on the Cornell box is the image of the same box whose materials are all Lambertian
//     0.8 grey (its emitter kept): the authored colours, the RT path's per-instance hit albedo
//     and legacy's voxel albedo all give way to 0.8;
//   - diffuse is Lambert with the authored base colour: a glossy plane under the sun and a
//     uniform sky shows no highlight, only base / pi (E cos + pi L), in every path;
//   - the modes change the image (the tests can fail).
#include "gpu_fixture.h"

#include "lighting/common/composite_pass.h"
#include "shared/color.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>
#include <functional>
#include <optional>

namespace tl::test {
namespace {

namespace fs = std::filesystem;

const char* kPaths[] = {"direct", "legacy", "rt", "reference"};

// A copy of a content scene with its JSON edited, in a temporary folder.
fs::path editedScene(const char* name, const std::function<void(nlohmann::json&)>& edit) {
  const fs::path dir = fs::temp_directory_path() / (std::string("twinlight-materials-") + name);
  fs::create_directories(dir);
  auto j = nlohmann::json::parse(std::ifstream(contentFile(name)));
  edit(j);
  std::ofstream(dir / name) << j.dump();
  const std::string bin = fs::path(name).replace_extension(".bin").string();
  fs::copy_file(contentFile(bin.c_str()), dir / bin, fs::copy_options::overwrite_existing);
  return dir / name;
}

class MaterialModeTest : public RayTracingTest {
 protected:
  // The final image (RGBA texels) of `frames` frames of `path` on `scene` in `mode`, under
  // `light` (the scene's own when absent). Frames count from 0 each time: every per-frame
  // pattern (rays, AO rotations) repeats, so equal inputs give equal images.
  std::vector<float> render(const fs::path& scene, const std::string& path, lighting::MaterialMode mode,
                            uint32_t frames, uint32_t size = 32, std::optional<session::Lighting> light = {}) {
    auto& s = session();
    s.loadScene(scene);
    if (light) s.setLighting(*light);
    s.setFrameIndex(0);
    s.setPath(path);
    s.setSize(size, size);
    s.settings().materials = mode;
    s.settings().referenceSamplesPerFrame = 16;
    s.resetHistory();
    s.renderFrames(frames - 1);
    s.requestBuffer(finalImageOf(path));
    s.renderFrames(1);
    return s.buffer(finalImageOf(path)).texels();
  }
};

// The largest difference between two images, relative to the value where it exceeds 1 (the
// lamp's pixels sit near 15, where half floats step by 2^-7), absolute below.
double largestDifference(const std::vector<float>& a, const std::vector<float>& b) {
  double d = 0.0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i)
    d = std::max(d, std::abs(double(a[i]) - b[i]) / std::max(1.0, std::abs(double(b[i]))));
  return a.size() == b.size() ? d : 1e30;
}

double meanRelativeDifference(const std::vector<float>& a, const std::vector<float>& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i)
    sum += std::abs(double(a[i]) - b[i]) / std::max(1.0, std::abs(double(b[i])));
  return a.size() == b.size() && !a.empty() ? sum / double(a.size()) : 1e30;
}

uint32_t framesFor(const std::string& path) { return path == "direct" ? 1 : (path == "reference" ? 4 : 8); }

TEST_F(MaterialModeTest, ClayIsTheSceneAllInLambertianGrey) {
  // Every material 0.8 grey, dielectric, roughness 1, untextured; emission as authored. Shaded
  // as diffuse (Lambert with the base colour), it is what clay makes of the original.
  const fs::path grey = editedScene("cornell.gltf", [](nlohmann::json& j) {
    for (auto& m : j["materials"]) {
      m["pbrMetallicRoughness"] = {{"baseColorFactor", {0.8, 0.8, 0.8, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}};
    }
  });
  // A dim sky besides the lamp, so that the direct path (which has no bounce light) shades too.
  session().loadScene(contentFile("cornell.gltf"));
  session::Lighting light = session().lighting();
  light.skyRadiance = glm::vec3(0.5f);
  for (const std::string path : kPaths) {
    const uint32_t frames = framesFor(path);
    const auto clay = render(contentFile("cornell.gltf"), path, lighting::MaterialMode::Clay, frames, 32, light);
    const auto greyDiffuse = render(grey, path, lighting::MaterialMode::Diffuse, frames, 32, light);
    const auto authored = render(contentFile("cornell.gltf"), path, lighting::MaterialMode::Authored, frames, 32, light);
    const double same = largestDifference(clay, greyDiffuse), changed = largestDifference(clay, authored);
    std::printf("cornell, %-9s clay vs all-grey diffuse: largest difference %.2e, mean %.2e; clay vs authored %.3f\n",
                path.c_str(), same, meanRelativeDifference(clay, greyDiffuse), changed);
    // The same inputs through the same code, but for the 8-bit storage of the grey scene's base
    // colour in the G-buffer (0.8 -> 0.799; clay shades with its 0.8 itself): within 0.5%. The
    // RT denoiser picks its radius from the local variance, so a 0.1% change of input can move
    // a lone pixel by a few percent: there the mean difference is what must vanish.
    const double meanDifference = meanRelativeDifference(clay, greyDiffuse);
    EXPECT_LT(meanDifference, 1e-3) << path;
    EXPECT_LT(same, path == "rt" ? 0.05 : 5e-3) << path;
    EXPECT_GT(changed, 0.05) << path << ": clay must change the image";
  }
  fs::remove_all(grey.parent_path());
}

TEST_F(MaterialModeTest, DiffuseHasNoSpecularHighlight) {
  // The plane made glossy (base 0.5, roughness 0.2), the sun mirrored by the centre pixel
  // towards the camera (which looks down at 45 degrees): as authored a highlight; diffuse is
  // Lambert, 0.5 / pi (E cos + pi L), on a plane nothing occludes.
  const fs::path glossy = editedScene("plane.gltf", [](nlohmann::json& j) {
    j["materials"][0]["pbrMetallicRoughness"] = {{"baseColorFactor", {0.5, 0.5, 0.5, 1.0}}, {"metallicFactor", 0.0},
                                                 {"roughnessFactor", 0.2}};
  });
  auto& s = session();
  const float E = 3.0f, L = 1.0f;
  s.loadScene(glossy);
  session::Lighting light = s.lighting();
  light.sunDirection = glm::normalize(glm::dvec3(0.0, -1.0, 1.0));  // travels towards +z and down: mirrored to (0, 3, 3)
  light.sunIrradiance = glm::vec3(E);
  light.skyRadiance = glm::vec3(L);
  for (const std::string path : kPaths) {
    const uint32_t frames = framesFor(path), size = 32;
    auto centre = [&](const std::vector<float>& t) {
      double sum = 0.0;
      for (uint32_t y = size / 2 - 1; y <= size / 2; ++y)
        for (uint32_t x = size / 2 - 1; x <= size / 2; ++x) sum += t[(size_t(y) * size + x) * 4 + 1];
      return sum / 4.0;
    };
    // The G-buffer stores the base colour as 8-bit sRGB.
    const float base = shared::tlSrgbToLinear(glm::vec3(std::round(shared::tlLinearToSrgb(glm::vec3(0.5f)).x * 255.0f) / 255.0f)).x;
    const double cosSun = std::sqrt(0.5), lambert = path == "reference" ? 0.5 * (E * cosSun / M_PI + L)
                                                                         : base * (E * cosSun / M_PI + L);
    const double diffuse = centre(render(glossy, path, lighting::MaterialMode::Diffuse, frames, size, light));
    const double authored = centre(render(glossy, path, lighting::MaterialMode::Authored, frames, size, light));
    std::printf("glossy plane, %-9s centre: diffuse %.4f (Lambert %.4f), authored %.4f\n", path.c_str(), diffuse, lambert,
                authored);
    EXPECT_NEAR(diffuse, lambert, 0.03 * lambert) << path;
    EXPECT_GT(authored, 1.5 * lambert) << path << ": as authored the sun's highlight is there";
  }
  fs::remove_all(glossy.parent_path());
}

}  // namespace
}  // namespace tl::test
