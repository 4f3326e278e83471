// The shared BRDF (shaders/shared/shading.h) against physics, by quadratures of its evaluation
// that share nothing with the tables the build computed or with the sampler:
//   - energy: the directional albedo never exceeds 1, for every (cos theta, roughness, base
//     colour, metallic) on a grid, and is 1 within 1% for a white dielectric and a white metal
//     at roughness 1 (the multiple-scattering compensation at work; without it the same
//     quadrature sees the loss);
//   - the uniform-environment terms the real-time paths use are that albedo;
//   - reciprocity, the Lambert override surface, and the sampler's estimator (mean weight =
//     albedo, density = the pdf it reports);
//   - KHR_materials_ior / specular: a white dielectric still reflects everything at any F0 and
//     F90, and F0 from the ior is Fresnel's head-on reflectance.
#include "../common/fresnel.h"
#include "shared/sampling.h"
#include "shared/scene.h"
#include "shared/shading.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace tl::shared {
namespace {

constexpr double kPiD = 3.14159265358979323846;

vec3 viewAt(double mu) { return vec3(float(std::sqrt(std::max(0.0, 1.0 - mu * mu))), 0.0f, float(mu)); }

// Integral of g(l) over the upper hemisphere (n = +z) by a product midpoint rule in polar
// coordinates around `axis`, with the polar angle theta = pi t^2 so that the nodes crowd the
// axis, where a sharp lobe lives. Deterministic and independent of anything it checks.
template <class G>
glm::dvec3 hemisphereQuadrature(glm::dvec3 axis, G g, int nt = 384, int np = 160) {
  axis = glm::normalize(axis);
  glm::dvec3 helper = std::abs(axis.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
  glm::dvec3 b1 = glm::normalize(glm::cross(helper, axis)), b2 = glm::cross(axis, b1);
  glm::dvec3 sum(0.0);
  for (int i = 0; i < nt; ++i) {
    const double t = (i + 0.5) / nt, theta = kPiD * t * t, dtheta = 2.0 * kPiD * t / nt;
    const double st = std::sin(theta), ct = std::cos(theta);
    for (int j = 0; j < np; ++j) {
      const double phi = 2.0 * kPiD * (j + 0.5) / np;
      glm::dvec3 l = axis * ct + st * (std::cos(phi) * b1 + std::sin(phi) * b2);
      if (l.z <= 0.0) continue;
      sum += g(vec3(l)) * (st * dtheta * (2.0 * kPiD / np));
    }
  }
  return sum;
}

// Directional albedo rho(v) = integral of f(v, l) cos(l): the quadrature around the mirror
// direction of v.
glm::dvec3 directionalAlbedo(const SurfaceParams& s, double mu) {
  const vec3 n(0, 0, 1), v = viewAt(mu);
  return hemisphereQuadrature(glm::dvec3(-v.x, -v.y, v.z),
                              [&](vec3 l) { return glm::dvec3(tlBrdf(s, n, v, l)) * double(l.z); });
}

struct Material {
  const char* name;
  vec3 base;
  float metallic;
};
const Material kMaterials[] = {
    {"white dielectric", vec3(1.0f), 0.0f}, {"grey dielectric", vec3(0.5f), 0.0f},
    {"black dielectric", vec3(0.0f), 0.0f}, {"white metal", vec3(1.0f), 1.0f},
    {"grey metal", vec3(0.5f), 1.0f},       {"black metal", vec3(0.0f), 1.0f},
    {"half metal", vec3(1.0f), 0.5f},       {"gold", vec3(1.0f, 0.78f, 0.34f), 1.0f},
};
const double kCosines[] = {0.02, 0.1, 0.3, 0.6, 1.0};
const float kRoughnesses[] = {0.0f, 0.1f, 0.3f, 0.6f, 0.8f, 1.0f};

TEST(Brdf, DirectionalAlbedoNeverExceedsOne) {
  double worst = 0.0;
  for (const Material& m : kMaterials)
    for (float r : kRoughnesses)
      for (double mu : kCosines) {
        const glm::dvec3 a = directionalAlbedo(tlSurface(m.base, r, m.metallic), mu);
        for (int c = 0; c < 3; ++c) {
          worst = std::max(worst, a[c]);
          // The quadrature itself is good to ~1e-3 (the white cases below agree with 1 to that).
          EXPECT_LE(a[c], 1.002) << m.name << " roughness " << r << " cos " << mu;
          EXPECT_GE(a[c], 0.0) << m.name << " roughness " << r << " cos " << mu;
        }
      }
  std::printf("largest directional albedo on the grid: %.5f\n", worst);
}

TEST(Brdf, WhiteDielectricAndWhiteMetalReflectEverything) {
  for (float r : {0.3f, 0.6f, 1.0f})
    for (float metallic : {0.0f, 1.0f}) {
      double lo = 2.0, hi = 0.0;
      for (double mu : kCosines) {
        const double a = directionalAlbedo(tlSurface(vec3(1.0f), r, metallic), mu).x;
        lo = std::min(lo, a), hi = std::max(hi, a);
        EXPECT_NEAR(a, 1.0, 0.01) << "metallic " << metallic << " roughness " << r << " cos " << mu;
      }
      std::printf("white, metallic %.0f, roughness %.1f: albedo %.5f .. %.5f\n", metallic, r, lo, hi);
    }
}

// The control: the same quadrature on the lobes without the compensation (one microfacet
// bounce, glTF's plain Fresnel mix) sees the energy a rough white metal loses, and the
// uncompensated Lambert + GGX sum (the previous model) sees the energy it gains.
TEST(Brdf, WithoutCompensationTheQuadratureSeesTheLoss) {
  SurfaceParams metal = tlSurface(vec3(1.0f), 1.0f, 1.0f);
  metal.msFresnel = vec3(0.0f);
  const double single = directionalAlbedo(metal, 0.3).x;
  EXPECT_LT(single, 0.9) << "single scattering at roughness 1 loses 10-40%";
  std::printf("white metal, roughness 1, cos 0.3, single scattering only: %.4f\n", single);

  // Lambert (albedo 1) + GGX at F0 = 0.04 simply added: more than 1 at grazing angles.
  const vec3 n(0, 0, 1), v = viewAt(0.1);
  SurfaceParams s = tlSurface(vec3(1.0f), 1.0f, 0.0f);
  const glm::dvec3 added = hemisphereQuadrature(glm::dvec3(-v.x, 0.0, v.z), [&](vec3 l) {
    SurfaceParams spec = s;
    spec.msFresnel = vec3(0.0f);
    return glm::dvec3(tlBrdfSpecular(spec, n, v, l) + vec3(kInvPi)) * double(l.z);
  });
  EXPECT_GT(added.x, 1.05);
  std::printf("white Lambert + GGX added, cos 0.1: %.4f\n", added.x);
}

// What the real-time paths use under a uniform sky is the BRDF's albedo: a white surface under
// a sky of radiance L shows L, and a grey one its albedo, at every angle.
TEST(Brdf, EnvironmentTermsAreTheDirectionalAlbedo) {
  double worst = 0.0;
  for (const Material& m : kMaterials)
    for (float r : {0.1f, 0.5f, 1.0f})
      for (double mu : {0.05, 0.4, 1.0}) {
        SurfaceParams s = tlSurface(m.base, r, m.metallic);
        const glm::dvec3 a = directionalAlbedo(s, mu);
        const vec3 e = tlEnvironmentSpecular(s, float(mu)) + tlEnvironmentDiffuse(s, float(mu));
        EXPECT_EQ(e, tlEnvironmentAlbedo(s, float(mu)));
        for (int c = 0; c < 3; ++c) {
          worst = std::max(worst, std::abs(e[c] - a[c]));
          EXPECT_NEAR(e[c], a[c], 4e-3) << m.name << " roughness " << r << " cos " << mu;
        }
      }
  std::printf("environment terms vs quadrature: worst difference %.5f\n", worst);
  // White: exactly 1 by construction of the terms (to float rounding), whatever the angle.
  for (float r : {0.045f, 0.5f, 1.0f})
    for (float mu : {0.0f, 0.2f, 1.0f})
      for (float metallic : {0.0f, 1.0f})
        EXPECT_NEAR(tlEnvironmentAlbedo(tlSurface(vec3(1.0f), r, metallic), mu).x, 1.0f, 1e-5f);
}

TEST(Brdf, HemisphericalAlbedoIsTheCosineWeightedMean) {
  for (const Material& m : {kMaterials[1], kMaterials[4], kMaterials[7]})
    for (float r : {0.2f, 1.0f}) {
      SurfaceParams s = tlSurface(m.base, r, m.metallic);
      // 2 int rho(mu) mu dmu by the midpoint rule in mu^2 (so each node carries equal weight).
      const int k = 24;
      glm::dvec3 mean(0.0);
      for (int i = 0; i < k; ++i) mean += directionalAlbedo(s, std::sqrt((i + 0.5) / k)) / double(k);
      const vec3 h = tlHemisphericalAlbedo(s);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(h[c], mean[c], 4e-3) << m.name << " " << r;
    }
  EXPECT_NEAR(tlHemisphericalAlbedo(tlSurface(vec3(1.0f), 0.7f, 0.0f)).x, 1.0f, 1e-5f);
}

TEST(Brdf, IsReciprocalAndZeroBelowTheSurface) {
  const vec3 n(0, 0, 1);
  for (const Material& m : kMaterials)
    for (float r : {0.1f, 0.5f, 1.0f}) {
      SurfaceParams s = tlSurface(m.base, r, m.metallic);
      for (vec3 a : {glm::normalize(vec3(0.3f, 0.1f, 0.9f)), glm::normalize(vec3(-0.8f, 0.2f, 0.15f))})
        for (vec3 b : {glm::normalize(vec3(-0.2f, 0.5f, 0.6f)), glm::normalize(vec3(0.9f, -0.1f, 0.05f))}) {
          vec3 ab = tlBrdf(s, n, a, b), ba = tlBrdf(s, n, b, a);
          for (int c = 0; c < 3; ++c) EXPECT_NEAR(ab[c], ba[c], 1e-5f * std::max(1.0f, ab[c])) << m.name << " " << r;
        }
      EXPECT_EQ(tlBrdf(s, n, n, vec3(0.0f, 0.6f, -0.8f)), vec3(0.0f));
    }
}

TEST(Brdf, LambertSurfaceIsAlbedoOverPi) {
  SurfaceParams s = tlLambertSurface(vec3(0.8f, 0.5f, 0.2f));
  const vec3 n(0, 0, 1);
  for (vec3 v : {n, glm::normalize(vec3(0.9f, 0.0f, 0.1f))})
    for (vec3 l : {n, glm::normalize(vec3(-0.7f, 0.3f, 0.2f))}) {
      const vec3 f = tlBrdf(s, n, v, l);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(f[c], s.diffuse[c] * kInvPi, 1e-7f);
    }
  EXPECT_EQ(tlEnvironmentSpecular(s, 0.3f), vec3(0.0f));
  EXPECT_EQ(tlEnvironmentDiffuse(s, 0.3f), s.diffuse);
  EXPECT_EQ(tlHemisphericalAlbedo(s), s.diffuse);
  EXPECT_EQ(tlBrdfSpecularProbability(s, 0.5f), 0.0f);
  EXPECT_EQ(tlSurfaceWithRoughness(s, 0.2f).specular, 0.0f);
}

// The reference's estimator f cos / pdf at tlSampleBrdf's directions: its mean is the
// quadrature's albedo, and the pdf it divides by is a density of the directions drawn.
TEST(Brdf, SamplerEstimatesTheAlbedo) {
  const vec3 n(0, 0, 1);
  const int g = 256;
  for (const Material& m : {kMaterials[0], kMaterials[1], kMaterials[3], kMaterials[7]})
    for (float r : {0.1f, 0.5f, 1.0f})
      for (double mu : {0.05, 0.5, 1.0}) {
        SurfaceParams s = tlSurface(m.base, r, m.metallic);
        const vec3 v = viewAt(mu);
        const float p = tlBrdfSpecularProbability(s, float(mu));
        glm::dvec3 sum(0.0), sum2(0.0);
        for (int i = 0; i < g; ++i)
          for (int j = 0; j < g; ++j) {
            const vec2 u((i + 0.5f) / g, (j + 0.5f) / g);
            const float choice = tlUintToUnitFloat(tlPcgHash(uint(i * g + j)));
            const vec3 l = tlSampleBrdf(s, n, v, p, u, choice);
            const float pdf = tlBrdfPdf(s, n, v, l, p);
            if (!(pdf > 0.0f) || l.z <= 0.0f) continue;
            const glm::dvec3 w = glm::dvec3(tlBrdf(s, n, v, l)) * double(l.z / pdf);
            sum += w, sum2 += w * w;
          }
        const glm::dvec3 mean = sum / double(g * g);
        const glm::dvec3 a = directionalAlbedo(s, mu);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean[c], a[c], 0.01 * std::max(a[c], 0.05)) << m.name << " " << r << " " << mu;
        // The pdf integrates to at most 1 over the upper hemisphere (the visible normals send
        // a little below it).
        const double total = hemisphereQuadrature(glm::dvec3(-v.x, 0.0, v.z), [&](vec3 l) {
                               return glm::dvec3(tlBrdfPdf(s, n, v, l, p));
                             }).x;
        EXPECT_LE(total, 1.002) << m.name << " " << r << " " << mu;
        EXPECT_GT(total, 1.0 - p - 0.002) << m.name << " " << r << " " << mu << ": the cosine part alone";
        if (m.base.x == 1.0f && m.metallic == 0.0f && r == 1.0f) {
          const double variance = sum2.x / double(g * g) - mean.x * mean.x;
          std::printf("white dielectric, roughness 1, cos %.2f: estimator sd %.4f\n", mu, std::sqrt(std::max(variance, 0.0)));
        }
      }
}

// KHR_materials_clearcoat: a white dielectric or metal under a full coat still reflects all the
// light at every angle (quadrature of the BRDF against 1, at roughnesses the quadrature
// resolves); the reference's sampler, which draws from the coat's visible normals too, estimates
// that albedo; and a smooth black dielectric under a smooth coat reflects head-on what two
// interfaces of ior 1.5 do, 1 - (1 - 0.04)^2 = 0.0784 (closed form).
TEST(Brdf, ClearcoatKeepsEnergyAndAddsASecondInterface) {
  const vec3 n(0, 0, 1);
  for (float metallic : {0.0f, 1.0f})
    for (float r : {0.3f, 1.0f})
      for (float rc : {0.3f, 1.0f}) {
        const SurfaceParams s = tlSurfaceCoated(tlSurface(vec3(1.0f), r, metallic), 1.0f, rc);
        double lo = 2.0, hi = 0.0;
        for (double mu : kCosines) {
          const double a = directionalAlbedo(s, mu).x;
          lo = std::min(lo, a), hi = std::max(hi, a);
          EXPECT_NEAR(a, 1.0, 0.01) << "metallic " << metallic << " roughness " << r << " coat " << rc << " cos " << mu;
        }
        std::printf("white, metallic %.0f, roughness %.1f, coat roughness %.1f: albedo %.5f .. %.5f\n", metallic, r, rc,
                    lo, hi);
        const int g = 192;
        for (double mu : {0.2, 0.7, 1.0}) {
          const vec3 v = viewAt(mu);
          const float p = tlBrdfSpecularProbability(s, float(mu));
          double sum = 0.0;
          for (int i = 0; i < g; ++i)
            for (int j = 0; j < g; ++j) {
              const vec2 u((i + 0.5f) / g, (j + 0.5f) / g);
              const vec3 l = tlSampleBrdf(s, n, v, p, u, tlUintToUnitFloat(tlPcgHash(uint(i * g + j))));
              const float pdf = tlBrdfPdf(s, n, v, l, p);
              if (pdf > 0.0f && l.z > 0.0f) sum += double(tlBrdf(s, n, v, l).x) * double(l.z / pdf);
            }
          EXPECT_NEAR(sum / double(g * g), directionalAlbedo(s, mu).x, 0.01) << "sampler, cos " << mu;
        }
      }
  const SurfaceParams bare = tlSurface(vec3(0.0f), 0.05f, 0.0f);
  const SurfaceParams coated = tlSurfaceCoated(bare, 1.0f, 0.05f);
  const double a = directionalAlbedo(bare, 1.0).x, b = directionalAlbedo(coated, 1.0).x;
  std::printf("black dielectric head-on: bare %.5f (Fresnel 0.04), coated %.5f (two interfaces 0.0784)\n", a, b);
  EXPECT_NEAR(a, 0.04, 0.04 * 0.02);
  EXPECT_NEAR(b, 0.0784, 0.0784 * 0.02);
}

TEST(Brdf, TablesAreBoundedAndSmoothMirrorsReflectEverything) {
  for (uint r = 0; r < kBrdfLutRoughness; ++r)
    for (uint c = 0; c < kBrdfLutCosines; ++c) {
      const float s = tlBrdfSpecularNode((r * kBrdfLutCosines + c) * 2), b = tlBrdfSpecularNode((r * kBrdfLutCosines + c) * 2 + 1);
      EXPECT_GE(s, 0.0f);
      EXPECT_GE(b, 0.0f);
      EXPECT_LE(s + b, 1.0f + 1e-6f);
    }
  // The smoothest lobe loses nothing to masking away from grazing angles: E = 1, and F0 = 1
  // gives S + B = 1 there, F0 = 0 only Schlick's grazing term.
  const vec2 e = tlSpecularAlbedoSplit(1.0f, kBrdfMinRoughness);
  EXPECT_NEAR(e.x + e.y, 1.0f, 1e-3f);
  EXPECT_NEAR(e.y, 0.0f, 1e-4f);
}

// KHR_materials_ior and KHR_materials_specular keep the balance: a white dielectric reflects all
// it receives whatever its F0 and F90, each channel on its own where the specular is coloured
// (the diffuse layer takes what that channel's specular layer leaves).
TEST(Brdf, WhiteDielectricReflectsEverythingAtAnyIorAndSpecular) {
  struct Case {
    const char* name;
    float ior;
    vec3 color;
    float specular;
  };
  const Case cases[] = {{"ior 1 (no specular reflection)", 1.0f, vec3(1.0f), 1.0f},
                        {"ior 1.33", 1.33f, vec3(1.0f), 1.0f},
                        {"ior 2.5", 2.5f, vec3(1.0f), 1.0f},
                        {"ior 0 (Fresnel 1)", 0.0f, vec3(1.0f), 1.0f},
                        {"specular 0", 1.5f, vec3(1.0f), 0.0f},
                        {"specular 0.5, tinted colour", 1.5f, vec3(4.0f, 1.0f, 0.2f), 0.5f}};
  for (const Case& k : cases)
    for (float r : {0.3f, 1.0f}) {
      const vec4 fresnel = tlDielectricFresnel(k.ior, k.color, k.specular);
      double lo = 2.0, hi = 0.0;
      for (double mu : kCosines) {
        const glm::dvec3 a = directionalAlbedo(tlSurfaceSpecular(vec3(1.0f), r, 0.0f, vec3(fresnel), fresnel.w), mu);
        for (int c = 0; c < 3; ++c) {
          lo = std::min(lo, a[c]), hi = std::max(hi, a[c]);
          EXPECT_NEAR(a[c], 1.0, 0.01) << k.name << " roughness " << r << " cos " << mu << " channel " << c;
        }
      }
      std::printf("white dielectric, %s, roughness %.1f: albedo %.5f .. %.5f\n", k.name, r, lo, hi);
    }
}

// F0 from the ior is Fresnel's reflectance at normal incidence, ((n - 1) / (n + 1))^2 for
// unpolarised light: a black, smooth dielectric seen head-on reflects that much of a uniform sky.
TEST(Brdf, SmoothBlackDielectricReflectsFresnelsReflectanceHeadOn) {
  for (double n : {1.33, 1.5, 2.0, 2.42}) {
    const double exact = (n - 1.0) * (n - 1.0) / ((n + 1.0) * (n + 1.0));
    const vec4 fresnel = tlDielectricFresnel(float(n), vec3(1.0f), 1.0f);
    const double a = directionalAlbedo(tlSurfaceSpecular(vec3(0.0f), 0.1f, 0.0f, vec3(fresnel), fresnel.w), 1.0).x;
    std::printf("ior %.2f: head-on albedo %.5f, Fresnel %.5f\n", n, a, exact);
    EXPECT_NEAR(a / exact, 1.0, 0.02) << "ior " << n;
  }
}

// KHR_materials_transmission: what a white transmitting surface reflects (quadrature of the
// BRDF, at roughnesses the quadrature resolves) and what it passes (tlThinTransmittance) add up
// to all the light, at any share t and angle; and a smooth clear pane passes 1 - Fresnel's
// reflectance of its ior, tinted by its base colour, within 2.5% of the closed form up to 75
// degrees (Schlick's approximation in the model: 2.1% more than Fresnel's at 60 degrees).
TEST(Brdf, TransmittingSurfaceReflectsAndPassesAllTheLight) {
  for (float t : {0.5f, 1.0f})
    for (float r : {0.3f, 1.0f}) {
      const SurfaceParams s = tlSurfaceTransmitting(tlSurface(vec3(1.0f), r, 0.0f), t);
      double lo = 2.0, hi = 0.0;
      for (double mu : kCosines) {
        const double total = directionalAlbedo(s, mu).x + double(tlThinTransmittance(s, float(mu)).x);
        lo = std::min(lo, total), hi = std::max(hi, total);
        EXPECT_NEAR(total, 1.0, 0.01) << "transmission " << t << " roughness " << r << " cos " << mu;
      }
      std::printf("white pane, transmission %.1f, roughness %.1f: reflected + passed %.5f .. %.5f\n", t, r, lo, hi);
    }
  const vec3 amber(0.9f, 0.55f, 0.25f);
  const SurfaceParams pane = tlSurfaceTransmitting(tlSurface(amber, 0.0f, 0.0f), 1.0f);
  for (double mu : {1.0, 0.857, 0.5, 0.26}) {
    const vec3 passed = tlThinTransmittance(pane, float(mu));
    const double exact = 1.0 - tl::test::fresnelReflectance(1.5, mu);
    std::printf("amber pane at cos %.3f: passes %.5f of its colour, 1 - Fresnel %.5f\n", mu, passed.x / amber.x, exact);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(passed[c] / amber[c], exact, 0.025 * exact) << "cos " << mu << " channel " << c;
  }
  // Metal passes nothing; an opaque surface (t = 0) neither.
  EXPECT_EQ(tlThinTransmittance(tlSurfaceTransmitting(tlSurface(vec3(1.0f), 0.2f, 1.0f), 1.0f), 0.7f), vec3(0.0f));
  EXPECT_EQ(tlThinTransmittance(tlSurface(vec3(1.0f), 0.2f, 0.0f), 0.7f), vec3(0.0f));
}

}  // namespace
}  // namespace tl::shared
