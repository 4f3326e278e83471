#include "session/compare.h"

#include "session/settings_json.h"

#include "lighting/common/composite_pass.h"
#include "metrics/flip.h"
#include "metrics/metrics.h"
#include "session/image_io.h"
#include "session/report_html.h"
#include "shared/color.h"
#include "shared/tonemap.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>

namespace tl::session {
namespace {

constexpr const char* kReferenceVersion = "reference-3";  // bump when the path tracer changes


double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

std::string referenceKey(const Session& s, const CompareOptions& o) {
  const View& v = s.view();
  const Lighting& l = s.lighting();
  std::string text = fmt::format(
      "{}|{:x}|{},{},{}|{},{},{}|{}|{},{},{}|{},{},{}|{},{},{}|{}x{}|{}|{}", kReferenceVersion, s.scene().contentHash,
      v.position.x, v.position.y, v.position.z, v.forward.x, v.forward.y, v.forward.z, v.yfovRadians, l.sunDirection.x,
      l.sunDirection.y, l.sunDirection.z, l.sunIrradiance.x, l.sunIrradiance.y, l.sunIrradiance.z, l.skyRadiance.x,
      l.skyRadiance.y, l.skyRadiance.z, s.settings().width, s.settings().height, o.referenceSpp, o.referenceBounces);
  if (s.animated()) text += fmt::format("|t{}", s.animationTime());  // the pose of deforming meshes
  text += fmt::format("|ao{}", s.settings().rtAoRadius);  // reference.ao's radius (0: scaled to the scene)
  text += fmt::format("|m{}", lighting::materialModeName(s.settings().materials));
  return fmt::format("{:016x}", scene::hashBytes(text.data(), text.size()));
}

// How the reference ends its paths (shaders/reference/path.glsl), for the report.
std::string referenceBouncePolicy(uint32_t cap) {
  return fmt::format("Russian roulette from the 4th scattering event (survival = the path throughput's largest "
                     "component, at most 0.95), hard cap {} scattering events",
                     cap);
}

// The reference image and its per-stage quantities at the primary hit: AO at the AO radius
// (one channel) and the diffuse irradiance (sky + bounce light, no sun; 0 on the sky).
struct ReferenceImages {
  metrics::Image radiance, ao, irradiance;
};

metrics::Image channelOf(const graph::Readback& rb, uint32_t channel) {
  auto t = rb.texels();
  const uint32_t c = rb.channels();
  std::vector<float> v(size_t(rb.extent.width) * rb.extent.height);
  for (size_t i = 0; i < v.size(); ++i) v[i] = t[i * c + std::min(channel, c - 1)];
  return metrics::Image::fromTexels(rb.extent.width, rb.extent.height, 1, std::move(v));
}

ReferenceImages renderReference(Session& s, const CompareOptions& o, const Progress& progress, nlohmann::json& info) {
  const std::filesystem::path dir = o.cacheDir.empty() ? defaultReferenceCache() : o.cacheDir;
  const std::string key = referenceKey(s, o);
  const std::filesystem::path files[3] = {dir / (key + ".exr"), dir / (key + ".ao.exr"), dir / (key + ".irradiance.exr")};
  info = {{"spp", o.referenceSpp},
          {"bounces", o.referenceBounces},
          {"bouncePolicy", referenceBouncePolicy(o.referenceBounces)},
          {"materials", lighting::materialModeName(s.settings().materials)},
          {"scope", o.scope},
          {"cacheFile", files[0].string()}};
  const uint32_t w = s.settings().width, h = s.settings().height;
  std::optional<RgbImage> cached[3];
  bool hit = true;
  for (int i = 0; i < 3; ++i) {
    cached[i] = readExrRgb(files[i]);
    hit = hit && cached[i] && cached[i]->width == w && cached[i]->height == h;
  }
  if (hit) {
    info["cached"] = true;
    ReferenceImages r{metrics::Image::fromTexels(w, h, 3, std::move(cached[0]->rgb)), metrics::Image::filled(w, h, 1, 0.0f),
                      metrics::Image::fromTexels(w, h, 3, std::move(cached[2]->rgb))};
    for (size_t i = 0; i < r.ao.data.size(); ++i) r.ao.data[i] = cached[1]->rgb[3 * i];
    return r;
  }
  info["cached"] = false;
  s.setPath("reference");
  s.settings().referenceBounces = o.referenceBounces;
  s.settings().referenceSamplesPerFrame = std::min(o.referenceSpp, 16u);
  const uint32_t frames = std::max(1u, o.referenceSpp / s.settings().referenceSamplesPerFrame);
  s.resetHistory();
  for (uint32_t f = 0; f < frames; ++f) {
    // The irradiance pass runs only in frames that read its result: every frame here.
    s.requestBuffer("reference.irradiance");
    if (f + 1 == frames) s.requestBuffer("reference.radiance"), s.requestBuffer("reference.ao");
    s.renderFrames(1);
    if (progress) progress(fmt::format("reference {} spp", (f + 1) * s.settings().referenceSamplesPerFrame), double(f + 1) / frames);
  }
  ReferenceImages r{rgbImage(s.buffer("reference.radiance")), channelOf(s.buffer("reference.ao"), 0),
                    rgbImage(s.buffer("reference.irradiance"))};
  std::vector<float> aoRgb(r.ao.data.size() * 3);
  for (size_t i = 0; i < aoRgb.size(); ++i) aoRgb[i] = r.ao.data[i / 3];
  // The radiance file last: its presence is what a later run looks for first.
  writeExrRgb(files[2], w, h, r.irradiance.data);
  writeExrRgb(files[1], w, h, aoRgb);
  writeExrRgb(files[0], w, h, r.radiance.data);
  return r;
}

// Per-stage error over the pixels where the path drew a surface (the sky has no AO or
// irradiance): AO as mean absolute and RMS error, irradiance as relMSE (same epsilon as the
// image's) and RMSE. `irradianceMap` receives the per-pixel relMSE (0 on the sky).
nlohmann::json stageErrors(const metrics::Image& ao, const metrics::Image& irradiance, const std::vector<float>& depth,
                           const ReferenceImages& ref, std::vector<float>& irradianceMap) {
  // The surface pixels of each image side by side in one row: the metrics' own relMSE and
  // RMSE then average over exactly those.
  std::vector<size_t> surface;
  for (size_t i = 0; i < depth.size(); ++i)
    if (depth[i] > 0.0f) surface.push_back(i);
  irradianceMap.assign(depth.size(), 0.0f);
  if (surface.empty()) return nlohmann::json::object();
  auto gather = [&](const metrics::Image& image) {
    std::vector<float> v;
    for (size_t i : surface) v.insert(v.end(), &image.data[i * image.channels], &image.data[(i + 1) * image.channels]);
    return metrics::Image::fromTexels(uint32_t(surface.size()), 1, image.channels, std::move(v));
  };
  const metrics::Image aoTest = gather(ao), aoRef = gather(ref.ao), eTest = gather(irradiance), eRef = gather(ref.irradiance);
  double aoAbs = 0.0, aoRefSum = 0.0;
  for (size_t k = 0; k < surface.size(); ++k) aoAbs += std::abs(double(aoTest.data[k]) - aoRef.data[k]), aoRefSum += aoRef.data[k];
  const metrics::MetricResult rel = metrics::relMse(eTest, eRef);
  for (size_t k = 0; k < surface.size(); ++k) irradianceMap[surface[k]] = rel.errorMap.data[k];
  const double n = double(surface.size());
  auto finite = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  return {{"surfacePixels", surface.size()},
          {"ao", {{"buffer", lighting::kCompositeAo}, {"reference", "reference.ao"}, {"meanAbsError", finite(aoAbs / n)},
                  {"RMSE", finite(metrics::rmse(aoTest, aoRef).value)}, {"referenceMean", aoRefSum / n}}},
          {"irradiance", {{"buffer", lighting::kCompositeIrradiance}, {"reference", "reference.irradiance"},
                          {"relMSE", finite(rel.value)}, {"RMSE", finite(metrics::rmse(eTest, eRef).value)}}}};
}

}  // namespace

metrics::Image rgbImage(const graph::Readback& rb) {
  auto t = rb.texels();
  const uint32_t c = rb.channels(), w = rb.extent.width, h = rb.extent.height;
  std::vector<float> rgb(size_t(w) * h * 3);
  for (size_t i = 0; i < size_t(w) * h; ++i)
    for (uint32_t k = 0; k < 3; ++k) rgb[i * 3 + k] = t[i * c + std::min(k, c - 1)];
  return metrics::Image::fromTexels(w, h, 3, std::move(rgb));
}

metrics::Image displayEncode(const metrics::Image& linear, float exposure) {
  metrics::Image out = linear;
  for (size_t i = 0; i < out.data.size(); i += 3) {
    glm::vec3 c(linear.data[i], linear.data[i + 1], linear.data[i + 2]);
    glm::vec3 d = shared::tlLinearToSrgb(shared::tlTonemapAces(glm::max(c, glm::vec3(0.0f)) * exposure));
    out.data[i] = d.x, out.data[i + 1] = d.y, out.data[i + 2] = d.z;
  }
  return out;
}

std::filesystem::path defaultReferenceCache() {
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::filesystem::path(x) / "twinlight" / "reference";
  if (const char* h = std::getenv("HOME"); h && *h) return std::filesystem::path(h) / ".cache" / "twinlight" / "reference";
  return std::filesystem::temp_directory_path() / "twinlight-reference";
}

nlohmann::json runCompare(Session& s, const CompareOptions& options, const Progress& progress) {
  CompareOptions o = options;
  if (o.scope == "same") o.referenceBounces = 2;
  else if (o.scope != "full") throw SessionError(fmt::format("unknown reference scope `{}` (full or same)", o.scope));
  if (o.referenceSpp == 0 || (o.referenceSpp > 16 && o.referenceSpp % 16))
    throw SessionError("the reference sample count must be at most 16 or a multiple of 16");
  std::vector<CompareVariant> runs;
  for (const auto& p : o.paths) runs.push_back({p, p, nlohmann::json::object()});
  if (o.paths.empty() && o.variants.empty())
    for (auto& p : s.paths())
      if (p.available && p.name != "reference") runs.push_back({p.name, p.name, nlohmann::json::object()});
  for (const auto& v : o.variants) {
    if (std::any_of(runs.begin(), runs.end(), [&](auto& r) { return r.name == v.name; }))
      throw SessionError(fmt::format("two compared configurations are called `{}`", v.name));
    runs.push_back(v);
  }
  const lighting::RenderSettings baseSettings = s.settings();
  for (auto& run : runs) {
    auto all = s.paths();
    auto it = std::find_if(all.begin(), all.end(), [&](auto& p) { return p.name == run.path; });
    if (it == all.end() || !it->available)
      throw SessionError(fmt::format("cannot compare `{}`: {}", run.name, it == all.end() ? "no such path `" + run.path + "`"
                                                                                         : it->unavailableReason));
    applySettingsJson(baseSettings, run.settings);  // every variant is checked before anything renders
  }
  std::error_code ec;
  std::filesystem::create_directories(o.outDir, ec);
  const std::string previousPath = s.path();
  // Every path and the reference show the same pose of any deforming mesh: time stands still.
  const double animationTime = s.animationTime(), animationStep = s.animationStep();
  s.setAnimationStep(0.0);

  nlohmann::json refInfo;
  const ReferenceImages referenceImages = renderReference(s, o, progress, refInfo);
  const metrics::Image& reference = referenceImages.radiance;
  const float exposure = std::exp2(-s.exposureEv());
  metrics::Image referenceDisplay = displayEncode(reference, exposure);
  writeExrRgb(o.outDir / "reference.exr", reference.width, reference.height, reference.data);
  writePngRgb(o.outDir / "reference.png", referenceDisplay.width, referenceDisplay.height, referenceDisplay.data);

  nlohmann::json results = nlohmann::json::array();
  for (size_t i = 0; i < runs.size(); ++i) {
    const std::string& name = runs[i].name;
    s.setPath(runs[i].path);
    s.settings() = applySettingsJson(baseSettings, runs[i].settings);
    s.resetHistory();
    for (const char* n : {lighting::kCompositeAo, lighting::kCompositeIrradiance, "gbuffer.depth"}) s.requestBuffer(n);
    s.renderFrames(std::max(1u, o.framesPerPath));
    s.settings() = baseSettings;
    if (progress) progress("path " + name, double(i + 1) / runs.size());
    metrics::Image test = rgbImage(s.buffer(lighting::kCompositeHdr));
    metrics::Image testDisplay = displayEncode(test, exposure);

    auto rel = metrics::relMse(test, reference);
    auto rms = metrics::rmse(test, reference);
    double peak = 0.0;
    for (float v : reference.data) peak = std::max(peak, double(v));
    double psnr = metrics::psnr(test, reference, std::max(peak, 1e-6));
    auto ssim = metrics::ssim(testDisplay, referenceDisplay, 1.0);
    auto flip = metrics::flipLdr(testDisplay, referenceDisplay);
    auto hdrFlip = metrics::flipHdr(test, reference);

    std::string stem = "error_" + name;
    writeExrRgb(o.outDir / (name + ".exr"), test.width, test.height, test.data);
    writePngRgb(o.outDir / (name + ".png"), testDisplay.width, testDisplay.height, testDisplay.data);
    writeFalseColourPng(o.outDir / (stem + "_flip.png"), flip.errorMap.width, flip.errorMap.height, flip.errorMap.data, 1.0f);
    writeExrGray(o.outDir / (stem + "_relmse.exr"), rel.errorMap.width, rel.errorMap.height, rel.errorMap.data);
    // Per-stage error, for paths that go through the shared composite (not the reference).
    nlohmann::json stages = nlohmann::json::object();
    if (s.hasBuffer(lighting::kCompositeIrradiance)) {
      std::vector<float> irradianceMap;
      stages = stageErrors(channelOf(s.buffer(lighting::kCompositeAo), 0), rgbImage(s.buffer(lighting::kCompositeIrradiance)),
                           s.buffer("gbuffer.depth").texels(), referenceImages, irradianceMap);
      writeFalseColourPng(o.outDir / (stem + "_irradiance.png"), test.width, test.height, irradianceMap, 1.0f);
      stages["irradianceMap"] = stem + "_irradiance.png";
    }

    nlohmann::json passes = nlohmann::json::object();
    for (const auto& [pass, ms] : s.passGpuMs()) passes[pass] = median(ms);
    auto finite = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
    results.push_back({{"path", name},
                       {"lightingPath", runs[i].path},
                       {"settings", runs[i].settings},
                       {"frames", o.framesPerPath},
                       {"frameMs", median(s.frameGpuMs())},
                       {"passMs", passes},
                       {"relMSE", finite(rel.value)},
                       {"RMSE", finite(rms.value)},
                       {"PSNR", finite(psnr)},
                       {"SSIM", finite(ssim.value)},
                       {"FLIP", finite(flip.value)},
                       {"HDR-FLIP", finite(hdrFlip.value)},
                       {"image", name + ".png"},
                       {"flipMap", stem + "_flip.png"},
                       {"relMSEMap", stem + "_relmse.exr"},
                       {"stages", stages}});
  }
  s.setPath(previousPath);
  s.setAnimationTime(animationTime);
  s.setAnimationStep(animationStep);

  const auto& d = s.device();
  const View& v = s.view();
  nlohmann::json report = {
      {"scene", s.scene().name},
      {"sceneFile", s.scene().path.string()},
      {"sceneHash", fmt::format("{:016x}", s.scene().contentHash)},
      {"width", s.settings().width},
      {"height", s.settings().height},
      {"camera", {{"position", {v.position.x, v.position.y, v.position.z}}, {"forward", {v.forward.x, v.forward.y, v.forward.z}},
                  {"yfovDegrees", glm::degrees(v.yfovRadians)}}},
      {"exposureEV", s.exposureEv()},
      {"device", d.name()},
      {"driver", d.driver()},
      {"vulkan", fmt::format("{}.{}.{}", VK_API_VERSION_MAJOR(d.apiVersion()), VK_API_VERSION_MINOR(d.apiVersion()),
                             VK_API_VERSION_PATCH(d.apiVersion()))},
      {"twinlight", "0.1.0"},
      {"reference", refInfo},
      {"metrics", {{"relMSE", "mean over pixels and channels of (t - r)^2 / (r^2 + 0.01), linear radiance"},
                   {"RMSE", "linear radiance"},
                   {"PSNR", "linear radiance, peak = the reference's maximum"},
                   {"SSIM", "display-encoded luminance, 11x11 Gaussian window"},
                   {"FLIP", "LDR-FLIP of the display images, 67 pixels per degree"},
                   {"HDR-FLIP", "HDR-FLIP of the linear images"},
                   {"stages.ao", "the AO the composite applied (composite.ao) against reference.ao, over surface pixels"},
                   {"stages.irradiance",
                    "the diffuse irradiance the composite used (composite.irradiance: sky + bounce light, no sun) against "
                    "reference.irradiance, relMSE (same epsilon) over surface pixels"}}},
      {"paths", results}};
  std::ofstream(o.outDir / "report.json") << report.dump(2) << "\n";
  writeReportHtml(o.outDir / "report.html", report, o.outDir);
  return report;
}

}  // namespace tl::session
