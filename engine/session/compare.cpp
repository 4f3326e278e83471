#include "session/compare.h"

#include "session/settings_json.h"

#include "gpu/pipeline.h"
#include "lighting/common/composite_pass.h"
#include "lighting/common/gbuffer_pass.h"
#include "metrics/depth_attribution.h"
#include "metrics/flip.h"
#include "metrics/metrics.h"
#include "metrics/statistics.h"
#include "session/compare_significance.h"
#include "session/image_io.h"
#include "session/provenance.h"
#include "session/report_html.h"
#include "shared/brdf_tables.h"
#include "shared/color.h"
#include "shared/tonemap.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace tl::session {
namespace {

using metrics::median;

// What compare reads of the reference path beyond its image: its AO, irradiance, noise, depth
// split and shaders, by the names the path gives (lighting::PathReadouts).
lighting::PathReadouts referenceReadouts(const Session& s) {
  for (const PathInfo& p : s.paths())
    if (p.capabilities.isReference) return p.capabilities.readouts;
  throw SessionError("this build has no reference path to compare against");
}

// The reference's shaders as compiled (includes and all) and the BRDF tables they read: any
// change to the path tracer's GPU code gives new SPIR-V and so a new cache key, with no
// version to remember to bump.
uint64_t referenceSpirvHash(const Session& s) {
  std::vector<uint64_t> hashes;
  for (const std::string& shader : referenceReadouts(s).shaders) {
    const std::vector<uint32_t> words = gpu::loadSpirv(shader);
    hashes.push_back(scene::hashBytes(words.data(), words.size() * sizeof(uint32_t)));
  }
  // The shared BRDF's tables are data the shaders read (brdf.tables), not SPIR-V.
  hashes.push_back(scene::hashBytes(&shared::kBrdfTables, sizeof(shared::kBrdfTables)));
  return scene::hashBytes(hashes.data(), hashes.size() * sizeof(uint64_t));
}

// The cache file's name: the frame key's parts that hold values (the whole camera: position,
// orientation, projection with the size; the sun; the sky; the reference's settings), the
// scene's content hash (the key's scene part is a per-process upload id), the pose of
// deforming meshes, the sample count and the SPIR-V. The session's settings must be the ones
// the reference renders with.
std::string referenceKey(const Session& s, const CompareOptions& o) {
  using lighting::FramePart;
  const lighting::FrameKey key = s.frameKey();
  // A noise target stops the render at a frame its seeds decide: the target and the cap name
  // the image as well as a sample count does.
  const std::string samples = o.referenceNoise ? fmt::format("noise {} cap {}", *o.referenceNoise, o.referenceNoiseCap)
                                               : fmt::format("spp {}", o.referenceSpp);
  std::string text = fmt::format("{:x}|{:x}|{:x}|{:x}|{:x}|{:x}|scene {:x}|spirv {:x}|{}",
                                 key.hash(FramePart::CameraPosition), key.hash(FramePart::CameraOrientation),
                                 key.hash(FramePart::Projection), key.hash(FramePart::Sun), key.hash(FramePart::Sky),
                                 key.settingsOf("reference"), s.scene().contentHash, referenceSpirvHash(s), samples);
  if (s.animated()) text += fmt::format("|t{}", s.animationTime());  // the pose of deforming meshes and moving nodes
  return fmt::format("{:016x}", scene::hashBytes(text.data(), text.size()));
}

// How the reference ends its paths (shaders/reference/path.glsl), for the report.
std::string referenceBouncePolicy(uint32_t cap) {
  return fmt::format("Russian roulette from the 4th scattering event (survival = the path throughput's largest "
                     "component, at most 0.95), hard cap {} scattering events",
                     cap);
}

// The reference image and its per-stage quantities at the primary hit: AO at the AO radius
// (one channel) and the diffuse irradiance (sky + bounce light, no sun; 0 on the sky); and its
// radiance split by path depth (PathReadouts::byDepth: empty for another
// renderer's image).
struct ReferenceImages {
  lighting::PathReadouts names;  // the graph resources they were read from (empty for another renderer's image)
  metrics::Image radiance, ao, irradiance;
  std::vector<metrics::Image> byDepth;
  std::vector<metrics::Image> byLobe;  // PathReadouts::byLobe: the diffuse layer's, the specular lobes'
  // The standard error of each pixel's radiance per channel (reference.stderr); empty for
  // another renderer's image, whose noise is unknown.
  metrics::Image stdErr;
};

// What each depth group is called in reports, in PathReadouts::byDepth's order.
const std::vector<std::string>& depthGroupNames() {
  static const std::vector<std::string> names = {"direct", "bounce1", "bounce2", "bounce3plus"};
  return names;
}

metrics::Image channelOf(const graph::Readback& rb, uint32_t channel) {
  auto t = rb.texels();
  const uint32_t c = rb.channels();
  std::vector<float> v(size_t(rb.extent.width) * rb.extent.height);
  for (size_t i = 0; i < v.size(); ++i) v[i] = t[i * c + std::min(channel, c - 1)];
  return metrics::Image::fromTexels(rb.extent.width, rb.extent.height, 1, std::move(v));
}

ReferenceImages renderReference(Session& s, const CompareOptions& o, const Progress& progress, nlohmann::json& info) {
  const std::filesystem::path dir = o.cacheDir.empty() ? defaultReferenceCache() : o.cacheDir;
  s.settings().referenceBounces = o.referenceBounces;  // before the key, which holds the reference's settings
  const std::string key = referenceKey(s, o);
  const lighting::PathReadouts names = referenceReadouts(s);
  const std::vector<std::string>& depthBuffers = names.byDepth;
  const std::vector<std::string>& lobeBuffers = names.byLobe;
  // The radiance first: its presence is what a run looks for first (it is written last).
  std::vector<std::filesystem::path> files = {dir / (key + ".exr"), dir / (key + ".ao.exr"), dir / (key + ".irradiance.exr"),
                                              dir / (key + ".stderr.exr"), dir / (key + ".noise.json")};
  const size_t firstDepthFile = files.size();
  for (size_t g = 0; g < depthBuffers.size(); ++g) files.push_back(dir / fmt::format("{}.bounces{}.exr", key, g));
  const size_t firstLobeFile = files.size();
  for (size_t l = 0; l < lobeBuffers.size(); ++l) files.push_back(dir / fmt::format("{}.lobe{}.exr", key, l));
  info = {{"source", "path tracer"},
          {"spp", o.referenceSpp},
          {"bounces", o.referenceBounces},
          {"bouncePolicy", referenceBouncePolicy(o.referenceBounces)},
          {"materials", lighting::materialModeName(s.settings().materials)},
          {"scope", o.scope},
          {"cacheFile", files[0].string()}};
  if (o.referenceNoise) info["noiseTarget"] = {{"relativeStdError", *o.referenceNoise}, {"sampleCap", o.referenceNoiseCap}};
  const uint32_t w = s.settings().width, h = s.settings().height;
  std::vector<std::optional<RgbImage>> cached(files.size());
  std::optional<nlohmann::json> cachedNoise;
  bool hit = true;
  for (size_t i = 0; i < files.size(); ++i) {
    if (files[i].extension() == ".json") {
      std::ifstream in(files[i]);
      if (in) cachedNoise = nlohmann::json::parse(in, nullptr, false);
      hit = hit && cachedNoise && cachedNoise->is_object();
      continue;
    }
    cached[i] = readExrRgb(files[i]);
    hit = hit && cached[i] && cached[i]->width == w && cached[i]->height == h;
  }
  if (hit) {
    info["cached"] = true;
    ReferenceImages r{names, metrics::Image::fromTexels(w, h, 3, std::move(cached[0]->rgb)),
                      metrics::Image::filled(w, h, 1, 0.0f), metrics::Image::fromTexels(w, h, 3, std::move(cached[2]->rgb))};
    for (size_t i = 0; i < r.ao.data.size(); ++i) r.ao.data[i] = cached[1]->rgb[3 * i];
    r.stdErr = metrics::Image::fromTexels(w, h, 3, std::move(cached[3]->rgb));
    for (size_t g = 0; g < depthBuffers.size(); ++g)
      r.byDepth.push_back(metrics::Image::fromTexels(w, h, 3, std::move(cached[firstDepthFile + g]->rgb)));
    for (size_t l = 0; l < lobeBuffers.size(); ++l)
      r.byLobe.push_back(metrics::Image::fromTexels(w, h, 3, std::move(cached[firstLobeFile + l]->rgb)));
    info["noise"] = *cachedNoise;
    if (cachedNoise->contains("spp")) info["spp"] = (*cachedNoise)["spp"];
    return r;
  }
  info["cached"] = false;
  const std::string referencePath = s.referencePath();
  if (referencePath.empty()) throw SessionError("this build has no reference path to compare against");
  s.setPath(referencePath);
  s.resetHistory();
  s.setFrameIndex(0);  // the noise does not depend on what the process rendered before (see runCompare)
  // The irradiance and depth-split passes run only in frames that read their results: every
  // frame here, so the split holds the very samples of the radiance.
  auto request = [&](bool all) {
    s.requestBuffer(names.irradiance);
    for (const auto& b : depthBuffers) s.requestBuffer(b);
    for (const auto& b : lobeBuffers) s.requestBuffer(b);
    if (all) s.requestBuffer(names.image), s.requestBuffer(names.ambientOcclusion), s.requestBuffer(names.noise);
  };
  if (o.referenceNoise) {
    // Stopped by its noise: any frame may be the last, so each one reads the images back.
    NoiseTarget target;
    target.relativeStdError = *o.referenceNoise;
    target.maxSamples = o.referenceNoiseCap;
    const ReferenceConvergence run = s.renderReferenceUntilNoise(target, [&](const ReferenceConvergence& sofar) {
      request(true);
      if (progress && sofar.noise)
        progress(fmt::format("reference {} spp, noise {:.4f} (target {})", sofar.noise->samplesPerPixel(),
                             sofar.noise->relativeStdError, target.relativeStdError),
                 std::min(1.0, double(sofar.noise->samplesPerPixel()) / target.maxSamples));
    });
    info["noise"] = {{"reached", run.reached}};
  } else {
    s.settings().referenceSamplesPerFrame = std::min(o.referenceSpp, 16u);
    const uint32_t frames = std::max(1u, o.referenceSpp / s.settings().referenceSamplesPerFrame);
    for (uint32_t f = 0; f < frames; ++f) {
      request(f + 1 == frames);
      s.renderFrames(1);
      if (progress) progress(fmt::format("reference {} spp", (f + 1) * s.settings().referenceSamplesPerFrame), double(f + 1) / frames);
    }
    info["noise"] = nlohmann::json::object();
  }
  if (const auto noise = s.referenceNoise()) {
    info["noise"]["relativeStdError"] = noise->relativeStdError;
    info["noise"]["spp"] = noise->samplesPerPixel();
    info["spp"] = noise->samplesPerPixel();
  }
  ReferenceImages r{names, rgbImage(s.buffer(names.image)), channelOf(s.buffer(names.ambientOcclusion), 0),
                    rgbImage(s.buffer(names.irradiance))};
  r.stdErr = rgbImage(s.buffer(names.noise));
  for (const auto& b : depthBuffers) r.byDepth.push_back(rgbImage(s.buffer(b)));
  for (const auto& b : lobeBuffers) r.byLobe.push_back(rgbImage(s.buffer(b)));
  std::vector<float> aoRgb(r.ao.data.size() * 3);
  for (size_t i = 0; i < aoRgb.size(); ++i) aoRgb[i] = r.ao.data[i / 3];
  // The radiance file last: its presence is what a later run looks for first.
  for (size_t g = 0; g < depthBuffers.size(); ++g) writeExrRgb(files[firstDepthFile + g], w, h, r.byDepth[g].data);
  for (size_t l = 0; l < lobeBuffers.size(); ++l) writeExrRgb(files[firstLobeFile + l], w, h, r.byLobe[l].data);
  writeTextFile(files[4], info["noise"].dump(2) + "\n");
  writeExrRgb(files[3], w, h, r.stdErr.data);
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
          {"ao", {{"buffer", lighting::kCompositeAo}, {"reference", ref.names.ambientOcclusion}, {"meanAbsError", finite(aoAbs / n)},
                  {"RMSE", finite(metrics::rmse(aoTest, aoRef).value)}, {"referenceMean", aoRefSum / n}}},
          {"irradiance", {{"buffer", lighting::kCompositeIrradiance}, {"reference", ref.names.irradiance},
                          {"relMSE", finite(rel.value)}, {"RMSE", finite(metrics::rmse(eTest, eRef).value)}}}};
}

// Which share of each depth group of the reference a path's image holds, and what each group's
// missing light costs (metrics/depth_attribution.h); and the path's error against the
// reference truncated after 1, 2 and 3 groups (what --bounces 1, 2, 3 renders), exposure-
// normalised with the whole reference's factor: the truncation it resembles most says how
// many bounces it models.
nlohmann::json depthReport(const metrics::Image& test, const std::vector<metrics::Image>& byDepth,
                           const std::vector<std::string>& byDepthNames, double normalisation) {
  auto finite = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  const metrics::DepthAttribution a = metrics::attributeDepths(test, byDepth);
  nlohmann::json groups = nlohmann::json::array();
  for (size_t g = 0; g < byDepth.size(); ++g)
    groups.push_back({{"group", depthGroupNames()[g]},
                      {"buffer", byDepthNames[g]},
                      {"captured", finite(a.captured[g])},
                      {"missing", finite(a.missing[g])},
                      {"shareOfReference", finite(a.groupShare[g])}});
  nlohmann::json truncated = nlohmann::json::array();
  const metrics::Image testNormalised = metrics::scaled(test, normalisation);
  metrics::Image partial = metrics::Image::filled(test.width, test.height, 3, 0.0f);
  for (size_t k = 1; k < byDepth.size(); ++k) {
    for (size_t i = 0; i < partial.data.size(); ++i) partial.data[i] += byDepth[k - 1].data[i];
    truncated.push_back({{"bounces", k}, {"relMSE_norm", finite(metrics::relMse(testNormalised, metrics::scaled(partial, normalisation)).value)}});
  }
  // "captures 99% of emission and direct light, 97% of the first bounce and 12% of the rest",
  // naming only the groups the reference has light in.
  std::vector<std::string> parts;
  const std::pair<const char*, double> said[] = {
      {"emission and direct light", a.captured[0]}, {"the first bounce", a.captured[1]}, {"the rest", a.capturedFrom(2)}};
  for (const auto& [what, share] : said)
    if (std::isfinite(share)) parts.push_back(fmt::format("{:.0f}% of {}", 100.0 * share, what));
  std::string summary = parts.empty() ? "the reference has no light to attribute" : "captures ";
  for (size_t i = 0; i < parts.size(); ++i)
    summary += (i == 0 ? "" : i + 1 == parts.size() ? " and " : ", ") + parts[i];
  return {{"groups", groups},
          {"capturedBeyondFirstBounce", finite(a.capturedFrom(2))},
          {"excess", finite(a.excess)},
          {"truncated", truncated},
          {"tile", metrics::kAttributionTile},
          {"summary", summary}};
}

// What the surfaces reflect through each lobe, the path's against the reference's (PathReadouts::byLobe;
// composite.diffuse and composite.specular for a path through the composite): the share of the
// reference's light in each lobe the path holds (the ratio of their summed luminance), each
// lobe's share of the reference, and its relMSE_norm (both lobes' images scaled by the whole
// reference's factor). The reference's lobe images carry its noise: the figures are not
// corrected for it (a lobe's summed luminance averages it out; its relMSE_norm does not).
nlohmann::json lobeReport(const std::vector<metrics::Image>& test, const std::vector<metrics::Image>& reference,
                          double referenceLuminance, double normalisation) {
  auto finite = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  static const char* kNames[] = {"diffuse", "specular"};
  nlohmann::json lobes = nlohmann::json::object();
  std::vector<std::string> parts;
  for (size_t l = 0; l < reference.size() && l < test.size(); ++l) {
    const double testMean = metrics::meanLuminance(test[l]), referenceMean = metrics::meanLuminance(reference[l]);
    const double captured = referenceMean > 0.0 ? testMean / referenceMean : std::nan("");
    const double share = referenceLuminance > 0.0 ? referenceMean / referenceLuminance : std::nan("");
    lobes[kNames[l]] = {{"captured", finite(captured)},
                        {"shareOfReference", finite(share)},
                        {"relMSE_norm", finite(metrics::relMse(metrics::scaled(test[l], normalisation),
                                                               metrics::scaled(reference[l], normalisation))
                                                   .value)}};
    // A lobe under 1% of the reference's light is not worth a sentence.
    if (std::isfinite(captured) && share >= 0.01)
      parts.push_back(fmt::format("{:.0f}% of the {}", 100.0 * captured, kNames[l]));
  }
  std::string summary = parts.empty() ? "the reference has no reflected light to split" : "captures ";
  for (size_t i = 0; i < parts.size(); ++i) summary += (i == 0 ? "" : " and ") + parts[i];
  lobes["summary"] = summary;
  return lobes;
}

// Another renderer's image as the reference: it must be readable, of the size compare
// renders and finite everywhere (a NaN would make every figure meaningless).
metrics::Image readReferenceFile(const std::filesystem::path& file, uint32_t width, uint32_t height) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec))
    throw SessionError(fmt::format("reference image {}: no such file", file.string()));
  // Linear radiance, as the paths' own images are measured: a display-referred image (a PNG,
  // tonemapped and 8-bit) would be read as radiance and give meaningless figures.
  if (const std::string format = imageFileFormat(file); format != "EXR")
    throw SessionError(fmt::format("reference image {} is not an OpenEXR file ({}): compare needs the linear radiance "
                                   "of another renderer as EXR",
                                   file.string(), format.empty() ? "not an image format it knows" : "it is a " + format));
  std::optional<RgbImage> image = readExrRgb(file);
  if (!image) throw SessionError(fmt::format("reference image {}: cannot be read as an RGB EXR", file.string()));
  if (image->width != width || image->height != height)
    throw SessionError(fmt::format("reference image {} is {}x{}, but compare renders {}x{} (--size must match the "
                                   "reference's camera and size)",
                                   file.string(), image->width, image->height, width, height));
  const size_t bad = size_t(std::count_if(image->rgb.begin(), image->rgb.end(), [](float v) { return !std::isfinite(v); }));
  if (bad) throw SessionError(fmt::format("reference image {} holds {} non-finite value(s)", file.string(), bad));
  return metrics::Image::fromTexels(width, height, 3, std::move(image->rgb));
}

std::string lowercase(std::string text) {
  for (char& c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

}  // namespace

const std::vector<std::string>& gateMetrics() {
  static const std::vector<std::string> names = {"relMSE", "relMSE_norm", "RMSE", "RMSE_norm", "FLIP", "FLIP_norm", "HDR-FLIP"};
  return names;
}

std::vector<GateThreshold> parseFailAbove(const std::string& spec) {
  std::string known;
  for (const auto& m : gateMetrics()) known += (known.empty() ? "" : ", ") + m;
  std::vector<GateThreshold> out;
  std::stringstream items(spec);
  for (std::string item; std::getline(items, item, ',');) {
    const size_t eq = item.find('=');
    if (eq == std::string::npos || eq == 0)
      throw SessionError(fmt::format("--fail-above: `{}` is not METRIC=VALUE (e.g. relMSE=0.05,flip=0.1)", item));
    const std::string name = item.substr(0, eq), value = item.substr(eq + 1);
    auto it = std::find_if(gateMetrics().begin(), gateMetrics().end(), [&](auto& m) { return lowercase(m) == lowercase(name); });
    if (it == gateMetrics().end()) {
      const std::string l = lowercase(name);
      if (l == "psnr" || l == "ssim")
        throw SessionError(fmt::format("--fail-above: `{}` cannot gate, larger is better (gate on: {})", name, known));
      throw SessionError(fmt::format("--fail-above: unknown metric `{}` (gate on: {})", name, known));
    }
    double threshold = 0.0;
    try {
      size_t used = 0;
      threshold = std::stod(value, &used);
      if (used != value.size()) throw std::invalid_argument(value);
    } catch (const std::exception&) {
      throw SessionError(fmt::format("--fail-above: the threshold of {} `{}` is not a number", *it, value));
    }
    if (!std::isfinite(threshold) || threshold < 0.0)
      throw SessionError(fmt::format("--fail-above: the threshold of {} must be a number >= 0, not `{}`", *it, value));
    if (std::any_of(out.begin(), out.end(), [&](auto& t) { return t.metric == *it; }))
      throw SessionError(fmt::format("--fail-above: {} is given twice", *it));
    out.push_back({*it, threshold});
  }
  if (out.empty()) throw SessionError("--fail-above needs METRIC=VALUE[,...] (e.g. relMSE=0.05,flip=0.1)");
  return out;
}

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
  // Another renderer's image is checked before anything renders.
  std::optional<metrics::Image> external;
  if (!o.referenceFile.empty()) external = readReferenceFile(o.referenceFile, s.settings().width, s.settings().height);
  if (o.scope == "same") o.referenceBounces = 2;
  else if (o.scope != "full") throw SessionError(fmt::format("unknown reference scope `{}` (full or same)", o.scope));
  if (o.referenceSpp == 0 || (o.referenceSpp > 16 && o.referenceSpp % 16))
    throw SessionError("the reference sample count must be at most 16 or a multiple of 16");
  if (o.referenceNoise && !(*o.referenceNoise > 0.0 && std::isfinite(*o.referenceNoise)))
    throw SessionError(fmt::format("the reference's noise target must be a number > 0, not {}", *o.referenceNoise));
  if (o.referenceNoise && o.referenceNoiseCap < 16)
    throw SessionError("the reference's sample cap must be at least 16");
  std::vector<CompareVariant> runs;
  for (const auto& p : o.paths) runs.push_back({p, p, nlohmann::json::object()});
  if (o.paths.empty() && o.variants.empty())
    for (auto& p : s.paths())
      // Debug views (AO as grey) are not lighting: measured only when named.
      if (p.available && !p.capabilities.isReference && !p.capabilities.debugView) runs.push_back({p.name, p.name, nlohmann::json::object()});
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
    for (const char* size : {"width", "height"})
      if (run.settings.is_object() && run.settings.contains(size))
        throw SessionError(fmt::format("`{}` cannot change `{}`: every compared image has the reference's size", run.name, size));
  }
  std::error_code ec;
  std::filesystem::create_directories(o.outDir, ec);
  const std::string previousPath = s.path();
  // Every path and the reference show the same pose of any deforming mesh: time stands still.
  const double animationTime = s.animationTime(), animationStep = s.animationStep();
  s.setAnimationStep(0.0);

  nlohmann::json refInfo;
  ReferenceImages referenceImages;
  if (external) {
    referenceImages.radiance = std::move(*external);
    // The paths render with the session's material mode (compare an external diffuse-only image
    // with --materials diffuse).
    refInfo = {{"source", "file"},
               {"file", std::filesystem::absolute(o.referenceFile).string()},
               {"materials", lighting::materialModeName(s.settings().materials)}};
  } else {
    referenceImages = renderReference(s, o, progress, refInfo);
  }
  const metrics::Image& reference = referenceImages.radiance;
  const float exposure = std::exp2(-s.exposureEv());
  metrics::Image referenceDisplay = displayEncode(reference, exposure);
  // Exposure-normalised figures: both images scaled so the reference's mean luminance is 0.18.
  const double normalisation = metrics::exposureNormalisation(reference), referenceMean = metrics::meanLuminance(reference);
  refInfo["meanLuminance"] = referenceMean;
  refInfo["normalisation"] = normalisation;
  const metrics::Image referenceNormalised = metrics::scaled(reference, normalisation);
  const metrics::Image referenceNormalisedDisplay = displayEncode(reference, float(normalisation));
  // The reference's per-pixel variance (its standard error squared): what each figure's
  // expectation carries of its noise (compare_significance.h). None for another renderer's image.
  metrics::Image referenceVariance = referenceImages.stdErr;
  for (float& v : referenceVariance.data) v *= v;
  if (!referenceVariance.data.empty() && refInfo.contains("noise"))
    refInfo["noise"]["expectedRelMSE_norm"] = metrics::expectedRelMse(reference, referenceVariance, normalisation);
  const NoisyReference noisyReference{reference, referenceVariance, exposure, normalisation};
  if (!referenceImages.byDepth.empty()) {
    // The split's groups as shares of the reference, and how well they add up to it.
    metrics::Image sum = metrics::Image::filled(reference.width, reference.height, 3, 0.0f);
    for (const auto& g : referenceImages.byDepth)
      for (size_t i = 0; i < sum.data.size(); ++i) sum.data[i] += g.data[i];
    const metrics::DepthAttribution whole = metrics::attributeDepths(reference, referenceImages.byDepth);
    nlohmann::json groups = nlohmann::json::array();
    for (size_t g = 0; g < whole.groupShare.size(); ++g)
      groups.push_back({{"group", depthGroupNames()[g]}, {"buffer", referenceImages.names.byDepth[g]},
                        {"shareOfReference", whole.groupShare[g]}});
    double difference = 0.0, total = 0.0;
    for (size_t i = 0; i < sum.data.size(); ++i) difference += std::abs(double(sum.data[i]) - reference.data[i]), total += reference.data[i];
    refInfo["byDepth"] = {{"groups", groups}, {"sumRelativeError", total > 0.0 ? difference / total : 0.0}};
  }
  if (referenceImages.byLobe.size() == 2) {
    // Each lobe's share of the reference's light; the rest is what the camera sees directly.
    const double diffuse = metrics::meanLuminance(referenceImages.byLobe[0]),
                 specular = metrics::meanLuminance(referenceImages.byLobe[1]);
    refInfo["byLobe"] = {{"buffers", referenceImages.names.byLobe},
                         {"diffuseShare", referenceMean > 0.0 ? diffuse / referenceMean : 0.0},
                         {"specularShare", referenceMean > 0.0 ? specular / referenceMean : 0.0}};
  }
  writeExrRgb(o.outDir / "reference.exr", reference.width, reference.height, reference.data);
  writePngRgb(o.outDir / "reference.png", referenceDisplay.width, referenceDisplay.height, referenceDisplay.data);

  nlohmann::json results = nlohmann::json::array();
  for (size_t i = 0; i < runs.size(); ++i) {
    const std::string& name = runs[i].name;
    s.setPath(runs[i].path);
    s.settings() = applySettingsJson(baseSettings, runs[i].settings);
    s.resetHistory();
    // Every run starts at frame 0 (the frame index seeds per-frame noise and patterns): a
    // figure is the same whatever the process rendered before it, so a sweep split into
    // shards measures what one process does.
    s.setFrameIndex(0);
    // The last errorFrames frames are measured one by one; the times of every frame are kept.
    const uint32_t frames = std::max(1u, o.framesPerPath), measuredFrames = std::clamp(o.errorFrames, 1u, frames);
    std::vector<double> frameMs;
    std::vector<std::pair<std::string, std::vector<double>>> passMsAll;
    auto render = [&](uint32_t n) {
      for (graph::ImageName b :
           {lighting::kCompositeAo, lighting::kCompositeIrradiance, lighting::kCompositeDiffuseLobe,
            lighting::kCompositeSpecularLobe, lighting::gbuffer::kDepth})
        s.requestBuffer(b);
      s.renderFrames(n);
      frameMs.insert(frameMs.end(), s.frameGpuMs().begin(), s.frameGpuMs().end());
      for (const auto& passTimes : s.passGpuMs()) {
        const std::string& pass = passTimes.first;
        const std::vector<double>& ms = passTimes.second;
        auto it = std::find_if(passMsAll.begin(), passMsAll.end(), [&](const auto& p) { return p.first == pass; });
        if (it == passMsAll.end())
          passMsAll.push_back({pass, ms});
        else
          it->second.insert(it->second.end(), ms.begin(), ms.end());
      }
    };
    std::vector<nlohmann::json> frameSignificance;
    render(frames - measuredFrames + 1);
    for (uint32_t k = 1; k < measuredFrames; ++k) {
      frameSignificance.push_back(pathSignificance(rgbImage(s.buffer(lighting::kCompositeHdr)), noisyReference));
      render(1);
    }
    const nlohmann::json runSettings = settingsJson(s.settings());
    const bool redeferred = s.settings().redeferred;
    s.settings() = baseSettings;
    if (progress) progress("path " + name, double(i + 1) / runs.size());
    metrics::Image test = rgbImage(s.buffer(lighting::kCompositeHdr));
    metrics::Image testDisplay = displayEncode(test, exposure);

    auto rel = metrics::relMse(test, reference);
    auto rms = metrics::rmse(test, reference);
    double peak = 0.0;
    for (float v : reference.data) peak = std::max(peak, double(v));
    // PSNR is relative to the reference's peak: undefined (null in the report) for a black one.
    double psnr = peak > 0.0 ? metrics::psnr(test, reference, peak) : std::nan("");
    auto ssim = metrics::ssim(testDisplay, referenceDisplay, 1.0);
    auto flip = metrics::flipLdr(testDisplay, referenceDisplay);
    auto hdrFlip = metrics::flipHdr(test, reference);
    const metrics::Image testNormalised = metrics::scaled(test, normalisation);
    const double relNorm = metrics::relMse(testNormalised, referenceNormalised).value;
    // The ratio of the mean luminances: how much of the reference's light the path shows.
    const double testMean = metrics::meanLuminance(test);
    const double meanRatio = referenceMean > 0.0 ? testMean / referenceMean : std::nan("");
    const double rmsNorm = metrics::rmse(testNormalised, referenceNormalised).value;
    const double flipNorm = metrics::flipLdr(displayEncode(test, float(normalisation)), referenceNormalisedDisplay).value;

    std::string stem = "error_" + name;
    writeExrRgb(o.outDir / (name + ".exr"), test.width, test.height, test.data);
    writePngRgb(o.outDir / (name + ".png"), testDisplay.width, testDisplay.height, testDisplay.data);
    writeFalseColourPng(o.outDir / (stem + "_flip.png"), flip.errorMap.width, flip.errorMap.height, flip.errorMap.data, 1.0f);
    writeExrGray(o.outDir / (stem + "_relmse.exr"), rel.errorMap.width, rel.errorMap.height, rel.errorMap.data);
    // Per-stage error, for paths that go through the shared composite (not the reference).
    nlohmann::json stages = nlohmann::json::object();
    if (!external && s.hasBuffer(lighting::kCompositeIrradiance)) {
      std::vector<float> irradianceMap;
      stages = stageErrors(channelOf(s.buffer(lighting::kCompositeAo), 0), rgbImage(s.buffer(lighting::kCompositeIrradiance)),
                           s.buffer(lighting::gbuffer::kDepth).texels(), referenceImages, irradianceMap);
      writeFalseColourPng(o.outDir / (stem + "_irradiance.png"), test.width, test.height, irradianceMap, 1.0f);
      stages["irradianceMap"] = stem + "_irradiance.png";
    }

    // The split by lobe, where the path's composite made one: not under redeferred shading,
    // whose light table comes as the I-buffer's sums (composite.stages leaves it out).
    nlohmann::json lobes = nlohmann::json::object();
    if (!external && !referenceImages.byLobe.empty() && s.hasBuffer(lighting::kCompositeSpecularLobe) && !redeferred)
      lobes = lobeReport(
          {rgbImage(s.buffer(lighting::kCompositeDiffuseLobe)), rgbImage(s.buffer(lighting::kCompositeSpecularLobe))},
          referenceImages.byLobe, referenceMean, normalisation);
    const nlohmann::json bounces = referenceImages.byDepth.empty()
                                       ? nlohmann::json::object()
                                       : depthReport(test, referenceImages.byDepth, referenceImages.names.byDepth, normalisation);

    frameSignificance.push_back(pathSignificance(test, noisyReference));
    const nlohmann::json significance = combineFrameSignificance(frameSignificance);

    nlohmann::json passes = nlohmann::json::object();
    for (const auto& [pass, ms] : passMsAll) passes[pass] = median(ms);
    auto finite = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
    results.push_back({{"path", name},
                       {"lightingPath", runs[i].path},
                       {"overrides", runs[i].settings},
                       {"settings", runSettings},  // every setting it ran with: `render --settings` replays it
                       {"frames", o.framesPerPath},
                       {"frameMs", median(frameMs)},
                       // The middle half of the frames' times: how far apart two medians must
                       // be before one configuration is faster (tune's fronts).
                       {"frameMsQuartiles", {metrics::quantile(frameMs, 0.25), metrics::quantile(frameMs, 0.75)}},
                       {"passMs", passes},
                       {"relMSE", finite(rel.value)},
                       {"RMSE", finite(rms.value)},
                       {"PSNR", finite(psnr)},
                       {"SSIM", finite(ssim.value)},
                       {"FLIP", finite(flip.value)},
                       {"HDR-FLIP", finite(hdrFlip.value)},
                       {"meanRatio", finite(meanRatio)},
                       {"meanLuminance", finite(testMean)},
                       {"relMSE_norm", finite(relNorm)},
                       {"RMSE_norm", finite(rmsNorm)},
                       {"FLIP_norm", finite(flipNorm)},
                       {"image", name + ".png"},
                       {"flipMap", stem + "_flip.png"},
                       {"relMSEMap", stem + "_relmse.exr"},
                       {"stages", stages},
                       {"bounces", bounces},
                       {"lobes", lobes},
                       {"significance", significance}});
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
      {"settings", settingsJson(baseSettings)},  // before the variants' overrides
      {"camera", {{"position", {v.position.x, v.position.y, v.position.z}}, {"forward", {v.forward.x, v.forward.y, v.forward.z}},
                  {"yfovDegrees", glm::degrees(v.yfovRadians)}}},
      {"exposureEV", s.exposureEv()},
      {"device", d.name()},
      {"driver", d.driver()},
      {"vulkan", fmt::format("{}.{}.{}", VK_API_VERSION_MAJOR(d.apiVersion()), VK_API_VERSION_MINOR(d.apiVersion()),
                             VK_API_VERSION_PATCH(d.apiVersion()))},
      {"twinlight", twinlightJson()},
      {"reference", refInfo},
      {"metrics", {{"relMSE", "as rendered: mean over pixels and channels of (t - r)^2 / (r^2 + 0.01), linear radiance"},
                   {"RMSE", "as rendered: linear radiance"},
                   {"PSNR", "as rendered: linear radiance, peak = the reference's maximum (unchanged by exposure)"},
                   {"SSIM", "as rendered: display-encoded luminance at the report's exposure, 11x11 Gaussian window"},
                   {"FLIP", "as rendered: LDR-FLIP of the display images at the report's exposure, 67 pixels per degree"},
                   {"HDR-FLIP", "as rendered: HDR-FLIP of the linear images (its exposures come from the reference)"},
                   {"meanRatio", "the path's mean luminance over the reference's (1: as much light; null for a black reference)"},
                   {"meanLuminance", "the path's mean luminance (linear, before exposure)"},
                   {"relMSE_norm", "exposure-normalised: relMSE of both images scaled so the reference's mean luminance is "
                                   "0.18 (reference.normalisation), so a dark scene's figure means what a bright one's does"},
                   {"RMSE_norm", "exposure-normalised: RMSE of both images scaled as for relMSE_norm"},
                   {"FLIP_norm", "exposure-normalised: LDR-FLIP of the display images at the exposure that maps the "
                                 "reference's mean luminance to 0.18"},
                   {"stages.ao", "the AO the composite applied (composite.ao) against reference.ao, over surface pixels"},
                   {"stages.irradiance",
                    "the diffuse irradiance the composite used (composite.irradiance: sky + bounce light, no sun) against "
                    "reference.irradiance, relMSE (same epsilon) over surface pixels"},
                   {"bounces",
                    "per-bounce attribution against the reference split by path depth (direct: emission and direct "
                    "light; bounce1, bounce2, bounce3plus): in each 8x8 tile the path's mean luminance is credited to "
                    "the groups in depth order; captured = the share of a group's light it holds, missing = the "
                    "group's light it lacks as a fraction of the reference's, excess = light beyond the reference's; "
                    "truncated = relMSE_norm against the reference rendered with --bounces k (docs/accuracy.md)"}}},
      {"paths", results}};
  // Which form each figure of a path is in, for readers that do not parse the descriptions.
  report["forms"] = {{"asRendered", {"relMSE", "RMSE", "PSNR", "SSIM", "FLIP", "HDR-FLIP"}},
                     {"exposureNormalised", {"relMSE_norm", "RMSE_norm", "FLIP_norm"}}};
  report["significance"] = {
      {"metrics", significanceMetrics()},
      {"estimator",
       "each path's figure against the converged reference, the reference's noise (its per-pixel variance v, "
       "reference.stderr squared) taken out of the expectation: relMSE and relMSE_norm by the unbiased estimator of "
       "g(r) = (t - r)^2 / (r^2 + eps) from r^ ~ N(r, v) to the second order, g - v/2 g'' + v^2/8 g''''; FLIP and "
       "FLIP_norm by simulation-extrapolation (the figure at noise v, 2v and 3v, the quadratic through them at 0). "
       "value = the estimate, raw = against the noisy reference as rendered, [low, high] = its 95% interval from the "
       "reference's noise (docs/accuracy.md, Significance); with errorFrames > 1 (tune), the mean over the last frames, "
       "the interval widened by their spread"},
      {"ranking", "paths in order of value; `<` where neighbours' intervals part, `~` where they overlap (within noise)"},
      {"rankings", rankPaths(results)}};
  if (!o.failAbove.empty()) report["gate"] = evaluateGate(results, o.failAbove);
  writeTextFile(o.outDir / "report.json", report.dump(2) + "\n");
  writeReportHtml(o.outDir / "report.html", report, o.outDir);
  return report;
}

}  // namespace tl::session
