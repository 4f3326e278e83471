// The emitter table both ray tracers sample (lighting/common/emitter_table.h,
// shared/emitters.h): every triangle of every emitting instance, chosen in proportion to area x
// luminance through an alias table whose draw (tlAliasSlot, tlAliasKeepsSlot, as the shaders
// run it) has exactly the probabilities the table states; a point uniform on the chosen
// triangle; its pdf in solid angle.
#include "lighting/common/emitter_table.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <random>

namespace tl {
namespace {

using namespace shared;

// Draws `draws` triangles the way the shaders do (common/emitter_pick.glsl) from 32-bit uniforms.
std::vector<double> drawFrequencies(const std::vector<Emitter>& table, uint32_t draws, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<double> count(table.size(), 0.0);
  const uint32_t n = uint32_t(table.size());
  for (uint32_t i = 0; i < draws; ++i) {
    const uint32_t h = rng();
    const uint32_t slot = tlAliasSlot(h, n);
    count[tlAliasKeepsSlot(h, table[slot].p0.w) ? slot : table[slot].ids.z] += 1.0;
  }
  for (double& c : count) c /= draws;
  return count;
}

// Closed forms: a unit quad scaled 2x (area 4) beside a unit quad twice as bright (area 1,
// luminance 2x), a dark one (no entries) and one with a degenerate triangle (an entry of
// probability 0, never drawn).
TEST(EmitterTable, WeighsAreaTimesLuminanceAndDrawsWithItsProbabilities) {
  scene::Scene sc;
  scene::Mesh quad;
  for (glm::vec3 p : {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(1, 0, 1), glm::vec3(0, 0, 1)}) {
    scene::Vertex v{};
    v.position = p;
    quad.vertices.push_back(v);
  }
  quad.indices = {0, 1, 2, 0, 2, 3};
  sc.meshes.push_back(quad);
  quad.indices = {0, 1, 2, 0, 0, 1};  // the second triangle has no area
  sc.meshes.push_back(quad);
  scene::Instance big, small, dark, degenerate;
  big.transform = glm::scale(glm::translate(glm::dmat4(1.0), glm::dvec3(0, 3, 0)), glm::dvec3(2.0));
  small.transform = glm::translate(glm::dmat4(1.0), glm::dvec3(5, 0, 0));
  degenerate.mesh = 1;
  sc.instances = {big, small, dark, degenerate};
  const std::vector<glm::vec3> emission = {glm::vec3(1.0f), glm::vec3(2.0f), glm::vec3(0.0f), glm::vec3(1.0f)};
  const lighting::EmitterTable table = lighting::buildEmitterTable(sc, emission);
  ASSERT_EQ(table.entries.size(), 6u) << "two triangles per emitting quad, none for the dark one";
  EXPECT_EQ(table.firstOfInstance, (std::vector<uint32_t>{1, 3, 0, 5}));
  EXPECT_FLOAT_EQ(table.brightest, 2.0f);
  double area = 0.0, probability = 0.0;
  for (size_t k = 0; k < table.entries.size(); ++k) {
    const Emitter& e = table.entries[k];
    area += e.edge1.w;
    probability += e.edge2.w;
    EXPECT_EQ(e.ids.y, k % 2) << "the triangle of its mesh";
  }
  EXPECT_EQ(table.entries[4].ids.x, 3u);
  EXPECT_NEAR(area, 5.5, 1e-5);
  EXPECT_NEAR(probability, 1.0, 1e-6);
  EXPECT_EQ(table.entries[5].edge2.w, 0.0f) << "a triangle with no area cannot be drawn (nor hit)";
  // Power: 4 x 1 (big), 1 x 2 (small), 0.5 x 1 (the degenerate quad's good half): 8 / 13 big.
  EXPECT_NEAR(table.entries[0].edge2.w + table.entries[1].edge2.w, 4.0 / 6.5, 1e-6);
  EXPECT_NEAR(table.entries[0].p0.y, 3.0f, 1e-6) << "world space";

  const std::vector<double> seen = drawFrequencies(table.entries, 4000000, 7);
  for (size_t k = 0; k < seen.size(); ++k) {
    const double p = table.entries[k].edge2.w;
    EXPECT_NEAR(seen[k], p, 4.0 * std::sqrt(p * (1.0 - p) / 4e6) + 3.0 / 4e6) << "entry " << k;
  }
  EXPECT_EQ(seen[5], 0.0);

  // Uniform points: their mean lands on the centroid.
  const Emitter& e = table.entries[0];
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  glm::dvec3 mean(0.0);
  const int n = 20000;
  for (int i = 0; i < n; ++i) mean += glm::dvec3(tlEmitterPoint(e, vec2(uni(rng), uni(rng))));
  const glm::dvec3 centroid = glm::dvec3(e.p0) + (glm::dvec3(e.edge1) + glm::dvec3(e.edge2)) / 3.0;
  EXPECT_LT(glm::length(mean / double(n) - centroid), 0.02);
  // pdf (solid angle) = prob d^2 / (area |cos|), either face; the RT path's inverse is its inverse.
  EXPECT_NEAR(tlEmitterInversePdf(e, 9.0f, -0.5f), e.edge1.w * 0.5 / (9.0 * e.edge2.w), 1e-5);
  EXPECT_NEAR(tlEmitterSolidAnglePdf(e.edge2.w, e.edge1.w, 9.0f, -0.5f) * tlEmitterInversePdf(e, 9.0f, -0.5f), 1.0, 1e-5);
}

// The alias table over weights that span nine orders of magnitude, zeros among them: the
// probabilities it states are the weights' shares, and the draw has them.
TEST(EmitterTable, AliasTableDrawsSkewedWeightsExactly) {
  std::vector<double> weights;
  std::mt19937 rng(11);
  for (int i = 0; i < 200; ++i) weights.push_back(i % 17 == 0 ? 0.0 : std::pow(10.0, std::uniform_real_distribution<double>(-6, 3)(rng)));
  const lighting::AliasTable t = lighting::buildAliasTable(weights);
  double total = 0.0;
  for (double w : weights) total += w;
  double sum = 0.0;
  for (size_t i = 0; i < weights.size(); ++i) {
    EXPECT_NEAR(t.probability[i], weights[i] / total, 1e-6 * weights[i] / total + 1e-12) << i;
    if (weights[i] == 0.0) {
      EXPECT_EQ(t.probability[i], 0.0) << i;
    }
    sum += t.probability[i];
  }
  EXPECT_NEAR(sum, 1.0, 1e-12);
  std::vector<Emitter> table(weights.size());
  for (size_t i = 0; i < table.size(); ++i) table[i].p0.w = t.threshold[i], table[i].ids.z = t.alias[i];
  const uint32_t draws = 4000000;
  const std::vector<double> seen = drawFrequencies(table, draws, 5);
  for (size_t i = 0; i < seen.size(); ++i) {
    const double p = t.probability[i];
    EXPECT_NEAR(seen[i], p, 4.0 * std::sqrt(p * (1.0 - p) / draws) + 3.0 / draws) << i;
  }
  EXPECT_TRUE(lighting::buildAliasTable({}).probability.empty());
  EXPECT_EQ(lighting::buildAliasTable({0.0, 0.0}).probability, (std::vector<double>{0.0, 0.0}));
}

}  // namespace
}  // namespace tl
