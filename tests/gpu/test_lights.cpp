// Point and spot lights (the light table, shaders/shared/lights.h) in every path against closed
// forms, and each real-time path against the reference in a room lit only by lamps:
//   - a point light of I = 683 cd (I = 1 on Twinlight's scale) 2 m above content/plane.gltf
//     (Lambertian 0.8 in the diffuse material mode, no sun, black sky): the radiance at distance r
//     from the point under it is rho / pi * I cos(theta) / d^2 = rho / pi * 2 / (4 + r^2)^1.5, in
//     every path (a missing cosine is 41% off at the edge, a wrong unit 683x);
//   - a spot light's cone: KHR_lights_punctual's falloff across its edge;
//   - shadows: a box between a point light and the floor hides it in every path (shadow maps in
//     direct and legacy, shadow rays in rt and the reference);
//   - content/lamps.gltf: each path's mean radiance against the reference's.
#include "gpu_fixture.h"
#include "../common/form_factors.h"
#include "../common/test_scenes.h"

#include "lighting/common/composite_pass.h"
#include "lighting/common/lights_pass.h"
#include "shared/color.h"
#include "shared/lights.h"

#include <cmath>
#include <cstdio>

namespace tl::test {
namespace {

constexpr uint32_t kSize = 64;
constexpr double kHeight = 4.0;                 // the camera, looking straight down at the origin
constexpr double kTanHalfFov = 0.57735026919;   // 60 degrees vertical

// Distance on the plane y = 0 from the origin to what pixel (x, y) sees.
double planeRadius(uint32_t x, uint32_t y) {
  const double nx = (x + 0.5) / (kSize / 2.0) - 1.0, ny = (y + 0.5) / (kSize / 2.0) - 1.0;
  return kHeight * kTanHalfFov * std::hypot(nx, ny);
}

class LightsTest : public RayTracingTest {
 protected:
  // content/plane.gltf seen from 4 m straight above, no sun, black sky, Lambertian materials,
  // lit by `lights`; the final image of `path` after `frames` frames.
  std::vector<float> renderPlane(const std::string& path, const std::vector<scene::Light>& lights, uint32_t frames,
                                 std::unique_ptr<scene::Scene> scene = nullptr, const std::string& buffer = "",
                                 lighting::MaterialMode materials = lighting::MaterialMode::Diffuse) {
    auto& s = session();
    if (scene) s.installScene(std::move(scene));
    else s.loadScene(contentFile("plane.gltf"));
    s.setSize(kSize, kSize);
    session::View v;
    v.position = {0.0, kHeight, 0.0};
    v.forward = {0.0, -1.0, 0.0};
    v.up = {0.0, 0.0, -1.0};
    v.yfovRadians = float(2.0 * std::atan(kTanHalfFov));
    s.setView(v);
    session::Lighting l = s.lighting();
    l.sunIrradiance = glm::vec3(0.0f);
    l.skyRadiance = glm::vec3(0.0f);
    l.lights = lights;
    l.exposureEv = 0.0f;
    s.setLighting(l);
    s.settings().materials = materials;
    s.settings().referenceSamplesPerFrame = 16;
    s.setPath(path);
    const std::string read = buffer.empty() ? std::string(finalImageOf(path)) : buffer;
    s.requestBuffer(read);
    s.renderFrames(frames);
    return s.buffer(read).texels();
  }
  // The plane's albedo as the path sees it: the G-buffer holds it as 8-bit sRGB; the reference
  // reads the material.
  double albedo(const std::string& path) {
    const float rho = session().scene().materials[0].baseColorFactor.r;
    if (path == "reference") return rho;
    return shared::tlSrgbToLinear(glm::vec3(std::round(shared::tlLinearToSrgb(glm::vec3(rho)).r * 255.0f) / 255.0f)).r;
  }
};

scene::Light point(glm::dvec3 position, float candela) {
  scene::Light l;
  l.type = scene::LightType::Point;
  l.intensity = candela;
  l.position = position;
  return l;
}

double red(const std::vector<float>& texels, uint32_t x, uint32_t y) { return texels[(size_t(y) * kSize + x) * 4]; }

// Worst relative error (and where) of the pixels of row `y` from the centre outwards against L(r).
struct RowError {
  double worst = 0.0;
  uint32_t at = 0;
};
template <class F>
RowError rowError(const std::vector<float>& img, uint32_t y, F expected) {
  RowError e;
  for (uint32_t x = kSize / 2; x < kSize; x += 2) {
    const double want = expected(planeRadius(x, y));
    if (!(want > 1e-4)) continue;
    const double err = std::abs(red(img, x, y) / want - 1.0);
    if (err > e.worst) e.worst = err, e.at = x;
  }
  return e;
}

// Tolerances: half floats (1e-3), the G-buffer's normal encoding, and for the reference 16 x 4
// jittered samples over a pixel whose radiance varies by under 1% across it; legacy adds the
// voxel cones' own gathering of the lit plane (measured: none above half-float rounding).
struct PathTolerance {
  const char* path;
  uint32_t frames;
  double tolerance;
};
constexpr PathTolerance kPlanePaths[] = {{"direct", 1, 0.01}, {"legacy", 4, 0.01}, {"rt", 2, 0.01}, {"reference", 4, 0.02}};

TEST_F(LightsTest, PointLightOverAPlaneGivesICosThetaOverDSquaredInEveryPath) {
  for (const auto& p : kPlanePaths) {
    const auto img = renderPlane(p.path, {point({0.0, 2.0, 0.0}, 683.0f)}, p.frames);
    const double rho = albedo(p.path);
    const RowError e = rowError(img, kSize / 2, [&](double r) { return rho / shared::kPi * 2.0 / std::pow(4.0 + r * r, 1.5); });
    std::printf("%s: worst relative error %.4f at x = %u (r = %.2f m)\n", p.path, e.worst, e.at, planeRadius(e.at, kSize / 2));
    EXPECT_LT(e.worst, p.tolerance) << p.path << " at pixel x = " << e.at;
  }
}

TEST_F(LightsTest, SpotConeFallsOffAsKhrLightsPunctualSaysInEveryPath) {
  // 2 m up, pointing down, cone 15 / 30 degrees: full inside r = 0.54 m, dark beyond r = 1.15 m.
  scene::Light spot = point({0.0, 2.0, 0.0}, 683.0f);
  spot.type = scene::LightType::Spot;
  spot.innerConeAngle = glm::radians(15.0f);
  spot.outerConeAngle = glm::radians(30.0f);
  spot.direction = {0.0, -1.0, 0.0};
  const double cosInner = std::cos(glm::radians(15.0)), cosOuter = std::cos(glm::radians(30.0));
  for (const auto& p : kPlanePaths) {
    const auto img = renderPlane(p.path, {spot}, p.frames);
    const double rho = albedo(p.path);
    auto expected = [&](double r) {
      const double d = std::sqrt(4.0 + r * r), cosAngle = 2.0 / d;
      const double t = std::clamp((cosAngle - cosOuter) / (cosInner - cosOuter), 0.0, 1.0);
      return rho / shared::kPi * t * t * cosAngle / (d * d);
    };
    // Pixels well inside the falloff ramp (not at its kinks, where one pixel spans a change of slope).
    double worst = 0.0;
    uint32_t at = 0;
    for (uint32_t x = kSize / 2; x < kSize; ++x) {
      const double r = planeRadius(x, kSize / 2);
      if (r > 1.1 || std::abs(r - 2.0 * std::tan(glm::radians(15.0))) < 0.08) continue;
      const double err = std::abs(red(img, x, kSize / 2) - expected(r)) / expected(0.0);
      if (err > worst) worst = err, at = x;
    }
    std::printf("%s: worst error %.4f of the centre's radiance at x = %u\n", p.path, worst, at);
    EXPECT_LT(worst, p.tolerance) << p.path;
    // Outside the outer cone nothing arrives.
    EXPECT_LT(std::abs(red(img, kSize - 2, kSize / 2)), 1e-3 * expected(0.0)) << p.path;
  }
}

// content/plane.gltf with a 1 m cube of the plane's material standing on it at the origin.
std::unique_ptr<scene::Scene> planeWithBox() {
  auto s = std::make_unique<scene::Scene>(scene::loadGltf(contentFile("plane.gltf")));
  auto cube = makeCubeScene(s->materials[0], 1.0f, glm::vec3(0.0f, 0.5f, 0.0f));
  scene::Mesh mesh = cube->meshes[0];
  mesh.material = s->meshes[0].material;
  mesh.contentHash = scene::hashBytes(mesh.vertices.data(), mesh.vertices.size() * sizeof(scene::Vertex));
  s->contentHash ^= mesh.contentHash;
  scene::Instance box = cube->instances[0];
  box.name = "box";
  box.mesh = uint32_t(s->meshes.size());
  box.node = uint32_t(s->instances.size());
  s->meshes.push_back(std::move(mesh));
  s->instances.push_back(box);
  s->bounds.extend(box.worldBounds);
  return s;
}

TEST_F(LightsTest, ABoxHidesAPointLightInEveryPath) {
  // A 1 m cube on the floor under a light 2 m above the origin: the floor 0.85 m from the
  // cube's centre is seen by the camera (past the cube's top edge: from 4 m it sees the floor
  // beyond 0.67 m) but not by the light (the line to it crosses the top face at 0.43 m; the
  // floor is hidden out to 1 m). direct and legacy see it through the light's cube shadow map,
  // rt and the reference trace shadow rays: it is dark in all four. The floor 1.5 m out is lit:
  // E = I cos / d^2 there, plus what the cube's unlit sides bounce (nothing in direct).
  uint32_t hidden = kSize / 2, lit = kSize / 2;
  while (planeRadius(hidden, kSize / 2) < 0.82) ++hidden;
  while (planeRadius(lit, kSize / 2) < 1.5) ++lit;
  const double rHidden = planeRadius(hidden, kSize / 2), rLit = planeRadius(lit, kSize / 2);
  ASSERT_LT(rHidden, 0.9);
  ASSERT_LT(rLit, 1.6);
  for (const auto& p : kPlanePaths) {
    const std::string path = p.path;
    const auto img = renderPlane(path, {point({0.0, 2.0, 0.0}, 683.0f)}, p.frames, planeWithBox());
    const auto closedForm = [&](double r) { return albedo(path) / shared::kPi * 2.0 / std::pow(4.0 + r * r, 1.5); };
    const double dark = red(img, hidden, kSize / 2), bright = red(img, lit, kSize / 2);
    std::printf("%s: floor hidden by the cube %.5f (unshadowed %.5f); lit floor %.5f (closed form %.5f, ratio %.4f)\n",
                path.c_str(), dark, closedForm(rHidden), bright, closedForm(rLit), bright / closedForm(rLit));
    // Only light bounced off the cube's side may arrive where it hides the light.
    EXPECT_LT(dark, 0.03 * closedForm(rHidden)) << path;
    EXPECT_NEAR(bright / closedForm(rLit), 1.0, path == "direct" ? p.tolerance : 0.04) << path;
  }
}

// 256 point lights over the plane (symmetric in x and z, so the image's orientation does not
// matter): beyond kLightsLoopMax every pixel estimates the sum by resampled picks, noisy, and
// accumulates while nothing changes. On a plane nothing occludes, so the exact image is the sum
// rho / pi * sum I cos / d^2: the error after 16 frames must be about a quarter of one frame's
// (1/sqrt(16)), in the direct path (unshadowed) and in rt (shadow rays).
std::vector<scene::Light> symmetricLampGrid() {
  std::vector<scene::Light> lights;
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 16; ++j) {
      const double x = -3.75 + 0.5 * i, z = -3.75 + 0.5 * j;
      const double y = 0.8 + 0.1 * (std::abs(x) + std::abs(z));
      lights.push_back(point({x, y, z}, float(683.0 * (0.2 + 0.1 * std::fmod(std::abs(x) * 3.0 + std::abs(z), 2.0)))));
    }
  return lights;
}

double exactLampGrid(const std::vector<scene::Light>& lights, double rho, double x, double z) {
  double e = 0.0;
  for (const auto& l : lights) {
    const glm::dvec3 d = l.position - glm::dvec3(x, 0.0, z);
    const double d2 = glm::dot(d, d);
    e += double(l.intensity) / 683.0 * (d.y / std::sqrt(d2)) / d2;
  }
  return rho / shared::kPi * e;
}

TEST_F(LightsTest, ManyLightsConvergeToTheExactSumOverFrames) {
  const auto lights = symmetricLampGrid();
  ASSERT_GT(lights.size(), size_t(shared::kLightsLoopMax));
  for (const char* path : {"direct", "rt"}) {
    double error[2] = {0.0, 0.0}, meanRatio = 0.0;
    const uint32_t frames[2] = {1, 16};
    for (int k = 0; k < 2; ++k) {
      const auto img = renderPlane(path, lights, frames[k]);
      const double rho = albedo(path);
      double sum2 = 0.0, ref2 = 0.0, gotSum = 0.0, wantSum = 0.0;
      for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
          const double nx = (x + 0.5) / (kSize / 2.0) - 1.0, ny = (y + 0.5) / (kSize / 2.0) - 1.0;
          const double want = exactLampGrid(lights, rho, kHeight * kTanHalfFov * nx, kHeight * kTanHalfFov * ny);
          const double got = red(img, x, y);
          sum2 += (got - want) * (got - want);
          ref2 += want * want;
          gotSum += got;
          wantSum += want;
        }
      error[k] = std::sqrt(sum2 / ref2);
      meanRatio = gotSum / wantSum;
    }
    std::printf("%s: relative RMS error %.4f after 1 frame, %.4f after 16 (ratio %.2f), image mean %.4f of the exact\n",
                path, error[0], error[1], error[0] / error[1], meanRatio);
    // Unbiased noise falls as 1/sqrt(frames): 4x over 16 frames (measured 3.97 and 3.91); a
    // bias would level it off and move the image's mean (measured within 0.5% of the exact).
    EXPECT_GT(error[0] / error[1], 3.0) << path << ": the estimate does not converge like 1/sqrt(frames)";
    EXPECT_LT(error[1], 0.15) << path;
    EXPECT_NEAR(meanRatio, 1.0, 0.02) << path;
  }
}

// The mean radiance (luminance) of the final image of `path` on content/lamps.gltf at 96 x 54;
// `bounces`: the reference's scattering events; `feedback`: legacy's and rt's multi-bounce (the
// reuse of the last frame's image, and the RT path's radiance cache).
double lampsMean(session::Session& s, const std::string& path, uint32_t frames, uint32_t bounces, bool feedback) {
  s.loadScene(contentFile("lamps.gltf"));
  s.setSize(96, 54);
  s.setPath(path);
  s.settings().referenceSamplesPerFrame = 16;
  s.settings().referenceBounces = bounces;
  s.settings().rtScreenRadiance = feedback;
  s.settings().legacyScreenRadiance = feedback;
  s.settings().rtCacheMinGain = feedback ? lighting::RenderSettings{}.rtCacheMinGain : 2.0f;  // above 1: never
  s.setFrameIndex(0);
  s.requestBuffer(finalImageOf(path));
  s.renderFrames(frames);
  const auto img = s.buffer(finalImageOf(path)).texels();
  double sum = 0.0;
  for (size_t i = 0; i + 3 < img.size(); i += 4) sum += shared::tlLuminance(glm::vec3(img[i], img[i + 1], img[i + 2]));
  return sum / double(img.size() / 4);
}

TEST_F(LightsTest, EachPathLightsARoomOfLampsCloseToTheReference) {
  // content/lamps.gltf: a closed room lit only by two point lights and a spot. Each path's mean
  // radiance against the reference's (64 paths per pixel) with as many bounces as the path
  // computes: direct light only for the direct path; direct light and one bounce for legacy and
  // rt without their frame-to-frame feedback (their multi-bounce; with it, against every bounce:
  // legacy 0.461, rt 0.665, the interior deficit docs/accuracy.md describes). Tolerances are the measured
  // gaps with a margin, far below a lamp missing from a path (the spot alone is about a third of
  // the direct light) or a unit error (683x).
  auto& s = session();
  const double direct = lampsMean(s, "reference", 4, 1, true);
  const double oneBounce = lampsMean(s, "reference", 4, 2, true);
  ASSERT_GT(direct, 0.0);
  struct Case {
    const char* path;
    uint32_t frames;
    double reference, tolerance;
  };
  // Measured (96 x 54, lavapipe): direct 1.002 (shadow-mapped lamps; 1.036 unshadowed), legacy
  // 0.725 (cone-traced voxels; 0.771 while its lamps cast no shadow, too bright where the
  // missing shadow made up for missing GI), rt 1.001.
  const Case cases[] = {{"direct", 1, direct, 0.02}, {"legacy", 8, oneBounce, 0.30}, {"rt", 16, oneBounce, 0.05}};
  for (const auto& c : cases) {
    const double mean = lampsMean(s, c.path, c.frames, 64, false);
    std::printf("%s: mean radiance %.5f, reference %.5f (ratio %.3f)\n", c.path, mean, c.reference, mean / c.reference);
    EXPECT_NEAR(mean / c.reference, 1.0, c.tolerance) << c.path;
  }
  // With its multi-bounce (the cache switches itself on in a closed room), rt against every bounce.
  const double every = lampsMean(s, "reference", 4, 64, true);
  const double rtEvery = lampsMean(s, "rt", 32, 64, true);
  std::printf("rt with its multi-bounce: mean radiance %.5f, every bounce %.5f (ratio %.3f)\n", rtEvery, every, rtEvery / every);
  EXPECT_NEAR(rtEvery / every, 1.0, 0.10);
  std::printf("reference: direct light %.5f, direct light and one bounce %.5f\n", direct, oneBounce);
}

// Area lights (shared/area_lights.h) over content/plane.gltf against closed forms, L = 1 (683
// nits), facing down 2 m up, the radiance rho/pi E at distance r from the point under the centre:
//   - a disk of radius 0.5: E = pi F, F the point-to-parallel-disk form factor
//     (on the axis r^2 / (r^2 + h^2));
//   - a 1.2 x 0.6 m rectangle: E = pi F, F the parallel rectangle's (the corner formula summed
//     with signs).
// direct and legacy shade the analytic term (times the light's shadow map: nothing to hide it
// here), rt the same times shadow rays to points on the light, the reference samples the light and the BRDF (multiple importance
// sampling). Lights are not seen by the camera and block nothing: the camera 4 m up sees the
// plane through them.
// The rectangle [-w/2, w/2] x [-d/2, d/2] over the point (x, 0).
double centredRectFormFactor(double w, double d, double h, double x) {
  return rectFormFactor(-w / 2 - x, w / 2 - x, -d / 2, d / 2, h);
}

scene::Light areaLight(scene::LightType type, double h) {
  scene::Light l;
  l.type = type;
  l.intensity = 683.0f;
  l.position = {0.0, h, 0.0};
  l.direction = {0.0, -1.0, 0.0};
  l.widthAxis = {1.0, 0.0, 0.0};
  return l;
}

// Reference: 64 x 16 paths per pixel; its worst pixel of the row is noise (measured 3.5% and 4.9%
// at 256 paths, 1.7% and 2.2% at 1024: halved by four times the samples, so unbiased; the
// centre within 0.05%). direct, legacy, rt: measured 0.22% (half floats, the G-buffer's 8-bit
// albedo, the pixel's extent).
constexpr PathTolerance kAreaPaths[] = {{"direct", 1, 0.01}, {"legacy", 4, 0.01}, {"rt", 2, 0.01}, {"reference", 64, 0.03}};

TEST_F(LightsTest, AreaLightsOverAPlaneGiveTheirFormFactorsInEveryPath) {
  scene::Light disk = areaLight(scene::LightType::Disk, 2.0);
  disk.radius = 0.5f;
  scene::Light rect = areaLight(scene::LightType::Rect, 2.0);
  rect.width = 1.2f;
  rect.height = 0.6f;
  // The first image a fresh session renders here comes out 9.2% brighter whichever path draws it
  // (legacy first: legacy; direct first: direct; the same path later is exact): the fixture's
  // first frame, not the lights. It is rendered and thrown away.
  renderPlane("direct", {disk}, 1);
  for (const auto& p : kAreaPaths) {
    const double rho = albedo(p.path);
    const auto diskImg = renderPlane(p.path, {disk}, p.frames);
    const RowError d = rowError(diskImg, kSize / 2, [&](double r) { return rho * diskFormFactor(0.5, 2.0, r); });
    // The rectangle's long side runs along the image's x (the camera's right is +x).
    const auto rectImg = renderPlane(p.path, {rect}, p.frames);
    const RowError q = rowError(rectImg, kSize / 2, [&](double r) { return rho * centredRectFormFactor(1.2, 0.6, 2.0, r); });
    const double centre = red(diskImg, kSize / 2, kSize / 2) / (rho * diskFormFactor(0.5, 2.0, planeRadius(kSize / 2, kSize / 2)));
    std::printf("%s: disk worst relative error %.4f at x = %u (centre ratio %.4f); rectangle %.4f at x = %u\n", p.path, d.worst,
                d.at, centre, q.worst, q.at);
    EXPECT_LT(d.worst, p.tolerance) << p.path << " disk at pixel x = " << d.at;
    EXPECT_LT(q.worst, p.tolerance) << p.path << " rectangle at pixel x = " << q.at;
  }
}

TEST_F(LightsTest, ABoxHidesADiskLightInEveryPath) {
  // content/plane.gltf with a 1 m cube, a disk of radius 0.1 m 2 m above its centre: the floor
  // 0.72 to 0.80 m from the centre (a pixel past the cube's top edge for the camera, whose
  // jittered samples in the reference stay off the cube's bright top) sees none of the disk
  // (every line to it crosses the cube's top face). rt (shadow rays to points on the disk) and
  // the reference (next-event estimation) are dark there, and so are direct and legacy through
  // the disk's cube shadow map (drawn from its centre; the penumbra, 0.1 m wide here, from the
  // blockers' distance).
  scene::Light disk = areaLight(scene::LightType::Disk, 2.0);
  disk.radius = 0.1f;
  uint32_t hidden = kSize / 2, lit = kSize / 2;
  while (planeRadius(hidden, kSize / 2) < 0.75) ++hidden;
  while (planeRadius(lit, kSize / 2) < 1.5) ++lit;
  ASSERT_LT(planeRadius(hidden, kSize / 2), 0.77);
  for (const auto& p : kAreaPaths) {
    const std::string path = p.path;
    const auto img = renderPlane(path, {disk}, p.frames, planeWithBox());
    const double rho = albedo(path);
    const double open = rho * diskFormFactor(0.1, 2.0, planeRadius(hidden, kSize / 2));
    const double dark = red(img, hidden, kSize / 2), bright = red(img, lit, kSize / 2);
    const double brightWant = rho * diskFormFactor(0.1, 2.0, planeRadius(lit, kSize / 2));
    std::printf("%s: floor hidden by the cube %.5f (unshadowed %.5f); lit floor %.5f (closed form %.5f)\n", path.c_str(), dark, open,
                bright, brightWant);
    EXPECT_LT(dark, 0.05 * open) << path;
    EXPECT_NEAR(bright / brightWant, 1.0, path == "direct" ? 0.02 : 0.05) << path;  // the cube bounces light in the others
  }
}

// A downward area light of radiance 1 at height h over the origin, as points with their areas.
struct ShapePoint {
  double x, z, area;
};
std::vector<ShapePoint> diskPoints(double a) {
  constexpr int kRings = 96, kSectors = 192;
  std::vector<ShapePoint> points;
  for (int i = 0; i < kRings; ++i)
    for (int j = 0; j < kSectors; ++j) {
      const double r = a * std::sqrt((i + 0.5) / kRings), phi = 2.0 * shared::kPi * (j + 0.5) / kSectors;
      points.push_back({r * std::cos(phi), r * std::sin(phi), shared::kPi * a * a / (kRings * kSectors)});
    }
  return points;
}
std::vector<ShapePoint> rectPoints(double sizeX, double sizeZ) {
  constexpr int kSide = 160;
  std::vector<ShapePoint> points;
  for (int i = 0; i < kSide; ++i)
    for (int j = 0; j < kSide; ++j)
      points.push_back({sizeX * ((i + 0.5) / kSide - 0.5), sizeZ * ((j + 0.5) / kSide - 0.5), sizeX * sizeZ / (kSide * kSide)});
  return points;
}

// The irradiance such a light gives the floor point (x, 0, z), all of it (`occluded` false) or
// what passes the unit cube [-0.5, 0.5] x [0, 1] x [-0.5, 0.5]: the sum of cos cos / d^2 dA over
// the shape's points (the midpoint rule; the geometry alone, none of the renderer's code).
double irradianceAroundCube(const std::vector<ShapePoint>& shape, double h, double x, double z, bool occluded) {
  double e = 0.0;
  const glm::dvec3 f(x, 0.0, z), lo(-0.5, 0.0, -0.5), hi(0.5, 1.0, 0.5);
  for (const auto& q : shape) {
    const glm::dvec3 d = glm::dvec3(q.x, h, q.z) - f;
    if (occluded) {  // the segment f + t d, t in (0, 1), against the cube's slabs
      double t0 = 0.0, t1 = 1.0;
      for (int k = 0; k < 3; ++k) {
        if (std::abs(d[k]) < 1e-12) {
          if (f[k] < lo[k] || f[k] > hi[k]) t0 = 2.0;
          continue;
        }
        double ta = (lo[k] - f[k]) / d[k], tb = (hi[k] - f[k]) / d[k];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta), t1 = std::min(t1, tb);
      }
      if (t0 < t1) continue;  // hidden
    }
    const double d2 = glm::dot(d, d), c = d.y / std::sqrt(d2);
    e += c * c / d2 * q.area;
  }
  return e;
}

TEST_F(LightsTest, AnAreaLightsPenumbraBehindABoxFollowsThePartOfTheShapeInSight) {
  // Lights 2 m above the 1 m cube, facing down: the floor beyond the cube's edge (0.5 m) sees
  // part of the light over the cube's top edge, a penumbra as wide as the light's extent along x
  // times (2 - 1) / 1. Three shapes: a disk of radius 0.5 m (the penumbra 0.5 to 1.5 m, 14
  // pixels), a 1.2 x 0.3 m rectangle long along x (0.4 to 1.6 m) and the same turned along z
  // (0.85 to 1.15 m, 4 pixels): a filter that sees a rectangle as a disk of its area (radius
  // 0.34 m) gets both wrong. Each path's direct light on the floor there against the visible
  // share of the shape, integrated over the geometry: the light table's own buffer in the
  // real-time paths (lights.radiance: PCSS from the shape's cube map in direct and legacy, shadow
  // rays to points on it in rt, both accumulated over the frames), the reference with paths of one
  // event (its light off the cube's sides, which the floor lights, adds up to a tenth next to
  // them). A hard shadow from the centre (its edge at 1 m, where half the light is in sight) is
  // off by half the unshadowed light next to its edge; an unshadowed light by most of it at the
  // cube's foot.
  const double pixel = 2.0 * kHeight * kTanHalfFov / kSize;  // metres of floor across a pixel
  // Sanity of the quadrature: the unhidden disk's closed form far from the cube.
  ASSERT_NEAR(irradianceAroundCube(diskPoints(0.5), 2.0, 2.2, 0.0, true) / shared::kPi / diskFormFactor(0.5, 2.0, 2.2), 1.0, 2e-3);
  struct Shape {
    const char* name;
    scene::Light light;
    std::vector<ShapePoint> points;
  };
  scene::Light disk = areaLight(scene::LightType::Disk, 2.0);
  disk.radius = 0.5f;
  scene::Light alongX = areaLight(scene::LightType::Rect, 2.0);
  alongX.width = 1.2f;  // along widthAxis, +x
  alongX.height = 0.3f;
  scene::Light alongZ = alongX;
  alongZ.width = 0.3f;
  alongZ.height = 1.2f;
  const Shape shapes[] = {{"disk r 0.5", disk, diskPoints(0.5)},
                          {"rectangle 1.2 x 0.3 along x", alongX, rectPoints(1.2, 0.3)},
                          {"rectangle 1.2 x 0.3 along z", alongZ, rectPoints(0.3, 1.2)}};
  struct Case {
    const char* path;
    uint32_t frames;
    double worst, mean;  // tolerated errors in the penumbra, as shares of the unshadowed light there
  };
  // Measured (lavapipe), worst / mean, disk: direct 0.080 / 0.036, legacy 0.083 / 0.033 (PCSS,
  // 16 weighted taps turned each frame), rt 0.097 / 0.028 (4 weighted shadow rays a frame),
  // reference 0.055 / 0.018; the rectangles: see the printout and docs/accuracy.md.
  const Case cases[] = {{"direct", 8, 0.12, 0.05}, {"legacy", 8, 0.12, 0.05}, {"rt", 16, 0.15, 0.05}, {"reference", 64, 0.08, 0.03}};
  for (const auto& shape : shapes) {
    // The floor's pixels in the penumbra (the camera sees the floor past 0.67 m), on the row's
    // centre line (the scene is symmetric in z), with the unshadowed light and the light in sight.
    struct Pixel {
      uint32_t x;
      double at, open, want;
    };
    std::vector<Pixel> pixels;
    for (uint32_t x = kSize / 2; x < kSize; ++x) {
      const double wx = (x + 0.5 - kSize / 2.0) * pixel, wz = 0.5 * pixel;
      if (wx < 0.72 || wx > 1.7) continue;
      pixels.push_back({x, wx, irradianceAroundCube(shape.points, 2.0, wx, wz, false) / shared::kPi,
                        irradianceAroundCube(shape.points, 2.0, wx, wz, true) / shared::kPi});
    }
    ASSERT_GT(pixels.size(), 10u);
    // What the criteria make of the two wrong answers: a hard shadow from the centre must fail
    // at least one, and so must no shadow.
    double hardWorst = 0.0, hardMean = 0.0, openMean = 0.0;
    for (const auto& q : pixels) {
      const double hard = q.at > 1.0 ? q.open : 0.0;
      hardWorst = std::max(hardWorst, std::abs(hard - q.want) / q.open);
      hardMean += std::abs(hard - q.want) / q.open / pixels.size();
      openMean += (q.open - q.want) / q.open / pixels.size();
    }
    std::printf("%s: a hard shadow would err by %.3f at worst, %.3f on average; no shadow by %.3f on average\n", shape.name,
                hardWorst, hardMean, openMean);
    EXPECT_GT(hardWorst, 2.0 * 0.15) << shape.name;
    EXPECT_GT(openMean, 2.0 * 0.05) << shape.name;
    for (const auto& c : cases) {
      const bool reference = std::string(c.path) == "reference";
      const uint32_t bounces = session().settings().referenceBounces;
      if (reference) session().settings().referenceBounces = 1;
      const auto img = renderPlane(c.path, {shape.light}, c.frames, planeWithBox(), reference ? std::string() : std::string(lighting::kLightsRadiance));
      session().settings().referenceBounces = bounces;
      const double rho = albedo(c.path);
      double worst = 0.0, worstAt = 0.0, mean = 0.0;
      for (const auto& q : pixels) {
        const double err = std::abs(red(img, q.x, kSize / 2) - rho * q.want) / (rho * q.open);
        mean += err / pixels.size();
        if (err > worst) worst = err, worstAt = q.at;
        if (std::getenv("TL_DEBUG_PENUMBRA"))
          std::printf("  %.3f m: got %.5f want %.5f open %.5f\n", q.at, red(img, q.x, kSize / 2), rho * q.want, rho * q.open);
      }
      std::printf("%s, %s: penumbra worst error %.4f of the unshadowed light at %.2f m, mean %.4f over %zu pixels\n", shape.name,
                  c.path, worst, worstAt, mean, pixels.size());
      EXPECT_LT(worst, c.worst) << shape.name << ", " << c.path << " at " << worstAt << " m";
      EXPECT_LT(mean, c.mean) << shape.name << ", " << c.path;
    }
  }
}


// content/plane.gltf made a white metal of roughness `roughness` (its own content hash, so no
// history of the Lambertian plane is reused).
std::unique_ptr<scene::Scene> metalPlane(float roughness) {
  auto s = std::make_unique<scene::Scene>(scene::loadGltf(contentFile("plane.gltf")));
  s->materials[0].baseColorFactor = glm::vec4(1.0f);
  s->materials[0].metallic = 1.0f;
  s->materials[0].roughness = roughness;
  s->contentHash ^= 0x6D6574616C000000ull + uint64_t(roughness * 1000.0f);
  return s;
}

TEST_F(LightsTest, AGlossyFloorReflectsAPanelAsTheReferenceDoesInEveryPath) {
  // A 1 x 1 m panel of radiance 1 (683 nits) 2 m above a white metal floor of roughness 0.25,
  // the camera 4 m above looking down through it (lights are not drawn for the camera): the
  // highlight is the panel's blurred mirror image at the centre. Each path's mean radiance over
  // the highlight (floor within 0.3 m of the centre) and over its tail (0.6 to 1.2 m) against
  // the reference's (64 x 16 paths a pixel, its area lights weighted against the BRDF's rays).
  // The rasterising paths estimate the lobes with one point of the shape and one direction of
  // the lobe a frame (shared/area_specular.h), accumulated; the redeferred form adds the same
  // samples to the I-buffer. The representative direction they used before (the lobe in the
  // vector irradiance's direction: a point light of the panel's power) gave the highlight at
  // 1.72x and the tail at 0.65x in every path.
  scene::Light panel = areaLight(scene::LightType::Rect, 2.0);
  panel.width = 1.0f;
  panel.height = 1.0f;
  struct Region {
    double inner, outer;
  };
  const Region regions[] = {{0.0, 0.3}, {0.6, 1.2}};
  auto means = [&](const std::vector<float>& img) {
    std::vector<double> m;
    for (const Region& r : regions) {
      double sum = 0.0;
      int count = 0;
      for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
          const double d = planeRadius(x, y);
          if (d >= r.inner && d < r.outer) sum += red(img, x, y), ++count;
        }
      m.push_back(sum / count);
    }
    return m;
  };
  auto& settings = session().settings();
  const auto want = means(renderPlane("reference", {panel}, 64, metalPlane(0.25f), "", lighting::MaterialMode::Authored));
  struct Case {
    const char* name;
    const char* path;
    bool redeferred;
  };
  // Measured: within 1.5% everywhere (the estimate's noise over 64 frames and the regions'
  // pixels, and the reference's own).
  const Case cases[] = {{"direct", "direct", false}, {"direct, redeferred", "direct", true}, {"legacy", "legacy", false}, {"rt", "rt", false}};
  for (const Case& c : cases) {
    const bool redeferred = settings.redeferred;
    settings.redeferred = c.redeferred;
    const auto got = means(renderPlane(c.path, {panel}, 64, metalPlane(0.25f), "", lighting::MaterialMode::Authored));
    settings.redeferred = redeferred;
    for (size_t i = 0; i < got.size(); ++i) {
      std::printf("%s: floor %.1f-%.1f m: %.5f against the reference's %.5f (ratio %.4f)\n", c.name, regions[i].inner,
                  regions[i].outer, got[i], want[i], got[i] / want[i]);
      EXPECT_NEAR(got[i] / want[i], 1.0, 0.05) << c.name << ", floor " << regions[i].inner << "-" << regions[i].outer << " m";
    }
  }
}


TEST_F(LightsTest, AChangeOfMaterialModeRestartsTheLightTablesAccumulation) {
  // The glossy floor under the panel for 16 frames in the authored mode, then one frame in the
  // diffuse mode: lights.direct accumulates while nothing it depends on changes, and the surfaces
  // it shades are one of those things, so that frame is the white Lambertian floor's form factor
  // (within the area-light test's 1%), not a running mean that still holds 16 glossy frames.
  auto& s = session();
  const lighting::MaterialMode before = s.settings().materials;
  scene::Light panel = areaLight(scene::LightType::Rect, 2.0);
  panel.width = 1.0f;
  panel.height = 1.0f;
  renderPlane("direct", {panel}, 16, metalPlane(0.25f), "", lighting::MaterialMode::Authored);
  s.settings().materials = lighting::MaterialMode::Diffuse;
  s.requestBuffer(finalImageOf("direct"));
  s.renderFrames(1);
  const auto img = s.buffer(finalImageOf("direct")).texels();
  s.settings().materials = before;
  const RowError e = rowError(img, kSize / 2, [&](double r) { return centredRectFormFactor(1.0, 1.0, 2.0, r); });
  std::printf("diffuse frame after 16 glossy ones: worst relative error %.4f at x = %u\n", e.worst, e.at);
  EXPECT_LT(e.worst, 0.01) << "at pixel x = " << e.at;
}

}  // namespace
}  // namespace tl::test
