#include "session/buffer_health.h"

#include "gpu/formats.h"
#include "lighting/common/decoders.h"
#include "shared/color.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace tl::session {
namespace {

bool contains(const std::string& s, const char* what) { return s.find(what) != std::string::npos; }

// Half-float rounding of three values of magnitude m moves their RGB sum by up to ~3 * m *
// 2^-11; anything below -4e-3 * m is no rounding but a colour with a negative channel.
constexpr double kShColourTolerance = 4e-3;

BufferHealth shColourHealth(const graph::Readback& shY, const graph::Readback* coCg) {
  BufferHealth h;
  h.name = shY.name;
  h.check = "finite, valid SH colour";
  const std::vector<float> sh = shY.texels();
  const std::vector<float> chroma = coCg ? coCg->texels() : std::vector<float>();
  const uint32_t shChannels = shY.channels(), chromaChannels = coCg ? coCg->channels() : 0;
  const size_t pixels = shChannels ? sh.size() / shChannels : 0;
  const bool sameSize = coCg && chromaChannels >= 2 && chroma.size() / chromaChannels == pixels;
  for (size_t i = 0; i < pixels; ++i) {
    ++h.values;
    bool finite = true;
    for (uint32_t c = 0; c < shChannels; ++c) finite &= std::isfinite(sh[i * shChannels + c]);
    float co = 0.0f, cg = 0.0f;
    if (sameSize) {
      co = chroma[i * chromaChannels], cg = chroma[i * chromaChannels + 1];
      finite &= std::isfinite(co) && std::isfinite(cg);
    }
    if (!finite) {
      ++h.nonFinite;
      continue;
    }
    if (!sameSize) continue;
    const float l0 = sh[i * shChannels];
    const glm::vec3 rgb = shared::tlYCoCgToRgb(glm::vec3(l0, co, cg));
    const double scale = std::max({std::abs(double(l0)), std::abs(double(co)), std::abs(double(cg))});
    const double lowest = std::min({double(l0), double(rgb.x), double(rgb.y), double(rgb.z)});
    if (lowest < -kShColourTolerance * scale) {
      ++h.negative;
      h.mostNegative = std::min(h.mostNegative, lowest);
    }
  }
  return h;
}

BufferHealth plainHealth(const graph::Readback& r, bool nonNegative) {
  BufferHealth h;
  h.name = r.name;
  h.check = nonNegative ? "finite, >= 0" : "finite";
  for (float v : r.texels()) {
    ++h.values;
    if (!std::isfinite(v)) {
      ++h.nonFinite;
    } else if (nonNegative && v < 0.0f) {
      ++h.negative;
      h.mostNegative = std::min(h.mostNegative, double(v));
    }
  }
  return h;
}

}  // namespace

bool holdsNonNegativeValues(const std::string& name, const std::string& description) {
  // Signed by nature, whatever the description says.
  for (const char* signedPart : {"coCg", "CoCg", "shY", "difference", "motion", "normal", "Normal"})
    if (contains(name, signedPart)) return false;
  // A direction's components are signed, whatever else the texel holds (bentsky.history: the
  // mean escaping direction beside its visibility).
  if (contains(description, "direction")) return false;
  for (const char* quantity : {"radiance", "irradiance", "emitted", "emission", "AO", "ambient occlusion", "visibility",
                               "sum of"})
    if (contains(description, quantity)) return true;
  return false;
}

std::vector<BufferHealth> bufferHealth(const Session& session) {
  std::vector<BufferHealth> out;
  for (const auto& info : session.resources()) {
    if (info.desc.type != graph::ResourceType::Image || !session.hasBuffer(info.name)) continue;
    const auto kind = gpu::formatInfo(info.desc.format).kind;
    if (kind != gpu::TexelKind::Float && kind != gpu::TexelKind::Depth) continue;
    const graph::Readback& r = session.buffer(info.name);
    const auto spec = lighting::parseDecoderSpec(info.desc.decoder);
    if (spec.name == "sh-irradiance") {
      const auto it = spec.companions.find("coCg");
      const graph::Readback* coCg =
          it != spec.companions.end() && session.hasBuffer(it->second) ? &session.buffer(it->second) : nullptr;
      out.push_back(shColourHealth(r, coCg));
    } else {
      out.push_back(plainHealth(r, holdsNonNegativeValues(info.name, info.desc.description)));
    }
  }
  return out;
}

}  // namespace tl::session
