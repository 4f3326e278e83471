#include "scene/environment_map.h"

#include "scene/input_limits.h"
#include "scene/scene.h"
#include "shared/environment.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <xxhash.h>

#include <algorithm>
#include <cmath>

namespace tl::scene {

namespace {

// Centre direction of texel (c, r) in the map's frame.
glm::vec3 texelDirection(const EnvironmentMap& map, uint32_t c, uint32_t r) {
  return shared::tlEquirectDirection(glm::vec2((float(c) + 0.5f) / float(map.width), (float(r) + 0.5f) / float(map.height)));
}

}  // namespace

EnvironmentMap makeEnvironmentMap(uint32_t width, uint32_t height, std::vector<glm::vec3> radiance) {
  if (width == 0 || height == 0 || width > InputLimits::kMaxImageSide || height > InputLimits::kMaxImageSide ||
      uint64_t(width) * height > InputLimits::kMaxImagePixels)
    throw SceneError(fmt::format("{}x{} texels, not 1 to {} per side and at most {} Mpixel", width, height,
                                 InputLimits::kMaxImageSide, InputLimits::kMaxImagePixels >> 20));
  if (radiance.size() != size_t(width) * height)
    throw SceneError(fmt::format("{} texels for a {}x{} map", radiance.size(), width, height));
  for (size_t i = 0; i < radiance.size(); ++i) {
    const glm::vec3 t = radiance[i];
    for (int k = 0; k < 3; ++k)
      if (!(t[k] >= 0.0f && t[k] <= InputLimits::kMaxLight))
        throw SceneError(fmt::format("texel ({}, {}) has radiance {} (a finite value from 0 to {:g} expected)",
                                     i % width, i / width, t[k], InputLimits::kMaxLight));
  }
  EnvironmentMap m;
  m.width = width;
  m.height = height;
  m.radiance = std::move(radiance);
  XXH64_state_t* h = XXH64_createState();
  XXH64_reset(h, 0);
  XXH64_update(h, &m.width, sizeof m.width);
  XXH64_update(h, &m.height, sizeof m.height);
  XXH64_update(h, m.radiance.data(), m.radiance.size() * sizeof(glm::vec3));
  m.contentHash = XXH64_digest(h);
  XXH64_freeState(h);
  glm::dvec3 sum(0.0);
  for (uint32_t r = 0; r < m.height; ++r) {
    glm::dvec3 row(0.0);
    for (uint32_t c = 0; c < m.width; ++c) row += glm::dvec3(m.radiance[size_t(r) * m.width + c]);
    sum += row * environmentTexelSolidAngle(m, r);
  }
  m.meanRadiance = glm::vec3(sum / (4.0 * M_PI));
  return m;
}

EnvironmentMap loadEnvironmentMap(const std::filesystem::path& file) {
  auto fail = [&](const std::string& why) -> SceneError {
    return SceneError(fmt::format("environment map {}: {}", file.string(), why));
  };
  try {
    requireRegularFile(file, false);
  } catch (const InputFileError& e) {
    throw SceneError(fmt::format("environment map {}", e.what()));  // e names the file
  }
  auto in = OIIO::ImageInput::open(file.string());
  if (!in) throw fail(fmt::format("not a readable image ({})", OIIO::geterror()));
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || uint64_t(spec.width) > InputLimits::kMaxImageSide ||
      uint64_t(spec.height) > InputLimits::kMaxImageSide ||
      uint64_t(spec.width) * uint64_t(spec.height) > InputLimits::kMaxImagePixels)
    throw fail(fmt::format("{}x{} pixels, more than the {} per side and {} Mpixel allowed", spec.width, spec.height,
                           InputLimits::kMaxImageSide, InputLimits::kMaxImagePixels >> 20));
  if (spec.nchannels <= 0 || spec.nchannels > InputLimits::kMaxImageChannels)
    throw fail(fmt::format("{} channels, not 1 to {}", spec.nchannels, InputLimits::kMaxImageChannels));
  const int ch = spec.nchannels;
  const size_t texels = size_t(spec.width) * size_t(spec.height);
  std::vector<float> raw(texels * size_t(ch));
  if (!in->read_image(0, 0, 0, ch, OIIO::TypeDesc::FLOAT, raw.data())) throw fail(in->geterror());
  std::vector<glm::vec3> radiance(texels);
  for (size_t i = 0; i < texels; ++i) {
    const float* s = &raw[i * size_t(ch)];
    radiance[i] = ch >= 3 ? glm::vec3(s[0], s[1], s[2]) : glm::vec3(s[0]);  // grey (+ alpha): white light
  }
  try {
    EnvironmentMap m = makeEnvironmentMap(uint32_t(spec.width), uint32_t(spec.height), std::move(radiance));
    m.path = file;
    return m;
  } catch (const SceneError& e) {
    throw fail(e.what());
  }
}

double environmentTexelSolidAngle(const EnvironmentMap& map, uint32_t row) {
  const double t0 = M_PI * double(row) / map.height, t1 = M_PI * double(row + 1) / map.height;
  return 2.0 * M_PI / map.width * (std::cos(t0) - std::cos(t1));
}

std::vector<float> environmentTable(const EnvironmentMap& map) {
  const uint32_t w = map.width, h = map.height;
  std::vector<float> table(shared::tlEnvTableFloats(w, h), 0.0f);
  for (size_t i = 0; i < map.radiance.size(); ++i)
    for (int k = 0; k < 3; ++k) table[4 * i + size_t(k)] = map.radiance[i][k];
  // Weights in double: a 16k-wide row of tiny texels next to a sun must not lose either.
  std::vector<double> rowSum(h, 0.0), row(w + 1);
  for (uint32_t r = 0; r < h; ++r) {
    const double sinTheta = std::sin(M_PI * (r + 0.5) / h);
    row[0] = 0.0;
    for (uint32_t c = 0; c < w; ++c)
      row[c + 1] = row[c] + double(shared::tlLuminance(map.radiance[size_t(r) * w + c])) * sinTheta;
    rowSum[r] = row[w];
    const uint32_t base = shared::tlEnvConditionalOffset(w, h, r);
    // A black row samples its columns uniformly (it is never chosen, unless all are black).
    for (uint32_t c = 0; c <= w; ++c) table[base + c] = row[w] > 0.0 ? float(row[c] / row[w]) : float(c) / float(w);
    table[base + w] = 1.0f;
  }
  double total = 0.0;
  for (double s : rowSum) total += s;
  const uint32_t marginal = shared::tlEnvMarginalOffset(w, h);
  double acc = 0.0;
  for (uint32_t r = 0; r <= h; ++r) {
    table[marginal + r] = total > 0.0 ? float(acc / total) : float(r) / float(h);
    if (r < h) acc += rowSum[r];
  }
  table[marginal + h] = 1.0f;
  return table;
}

std::array<glm::vec4, 9> environmentSh9(const EnvironmentMap& map, float rotationRadians, float intensity) {
  std::array<glm::dvec3, 9> sum{};
  const glm::vec2 cs(std::cos(rotationRadians), std::sin(rotationRadians));
  for (uint32_t r = 0; r < map.height; ++r) {
    const double omega = environmentTexelSolidAngle(map, r);
    for (uint32_t c = 0; c < map.width; ++c) {
      const glm::vec3 d = shared::tlEnvMapToWorld(texelDirection(map, c, r), cs);
      const glm::dvec3 l = glm::dvec3(map.radiance[size_t(r) * map.width + c]) * omega;
      for (uint32_t i = 0; i < 9; ++i) sum[i] += l * double(shared::tlSh9Basis(i, d));
    }
  }
  std::array<glm::vec4, 9> sh;
  for (uint32_t i = 0; i < 9; ++i) sh[i] = glm::vec4(glm::vec3(sum[i] * double(intensity)), 0.0f);
  return sh;
}

std::optional<SunAndSky> separateEnvironmentSun(const EnvironmentMap& map) {
  const uint32_t w = map.width, h = map.height;
  const double meanLuminance = shared::tlLuminance(map.meanRadiance);
  size_t brightest = 0;
  float most = -1.0f;
  for (size_t i = 0; i < map.radiance.size(); ++i)
    if (const float l = shared::tlLuminance(map.radiance[i]); l > most) most = l, brightest = i;
  if (!(meanLuminance > 0.0) || double(most) < kSunContrast * meanLuminance) return std::nullopt;
  const glm::dvec3 peak(texelDirection(map, uint32_t(brightest % w), uint32_t(brightest / w)));
  const double cosSearch = std::cos(kSunSearchRadius), cosRing = std::cos(1.5 * kSunSearchRadius);
  // The sun's texels; the sky around it (a ring out to 1.5 search radii) fills them.
  std::vector<size_t> texels;
  glm::dvec3 irradiance(0.0), weighted(0.0), ring(0.0);
  double solidAngle = 0.0, ringSolidAngle = 0.0, total = 0.0;
  for (uint32_t r = 0; r < h; ++r) {
    const double omega = environmentTexelSolidAngle(map, r);
    for (uint32_t c = 0; c < w; ++c) {
      const size_t i = size_t(r) * w + c;
      const double l = shared::tlLuminance(map.radiance[i]);
      total += l * omega;
      const glm::dvec3 d(texelDirection(map, c, r));
      const double cosAngle = glm::dot(d, peak);
      if (cosAngle >= cosSearch && l > 0.05 * double(most)) {
        texels.push_back(i);
        irradiance += glm::dvec3(map.radiance[i]) * omega;
        weighted += d * (l * omega);
        solidAngle += omega;
      } else if (cosAngle >= cosRing) {
        ring += glm::dvec3(map.radiance[i]) * omega;
        ringSolidAngle += omega;
      }
    }
  }
  const double share = shared::tlLuminance(glm::vec3(irradiance)) / total;
  if (share < kSunShare || glm::length(weighted) <= 0.0) return std::nullopt;
  const glm::dvec3 around = ringSolidAngle > 0.0 ? ring / ringSolidAngle : glm::dvec3(0.0);
  SunAndSky out;
  out.sun.direction = glm::normalize(weighted);
  // What the sky behind it keeps is not the sun's: the two together hold the map's light exactly.
  out.sun.irradiance = glm::vec3(glm::max(irradiance - around * solidAngle, glm::dvec3(0.0)));
  out.sun.angularRadius = std::acos(std::clamp(1.0 - solidAngle / (2.0 * M_PI), -1.0, 1.0));
  out.sun.texels = uint32_t(texels.size());
  std::vector<glm::vec3> sky = map.radiance;
  for (size_t i : texels) sky[i] = glm::vec3(around);
  EnvironmentMap residual = makeEnvironmentMap(w, h, std::move(sky));
  residual.path = map.path;
  out.sky = std::make_shared<const EnvironmentMap>(std::move(residual));
  return out;
}

}  // namespace tl::scene
