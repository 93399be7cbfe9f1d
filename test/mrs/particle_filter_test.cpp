#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <vector>

#include "mrs_vpr/mrs/particle_filter.hpp"

namespace mrs_vpr {
namespace {

Particle particle(int index, double weight, float cost = 0.0F) {
  Particle p;
  p.index = index;
  p.weight = weight;
  p.cost = cost;
  return p;
}

double weightSum(const std::vector<Particle>& particles) {
  double sum = 0.0;
  for (const Particle& p : particles) sum += p.weight;
  return sum;
}

TEST(UpdateWeights, LowerCostGetsMoreWeightAndWeightsAreNormalised) {
  std::vector<Particle> particles{particle(0, 1.0 / 3, 1.0F), particle(1, 1.0 / 3, 2.0F), particle(2, 1.0 / 3, 3.0F)};
  updateWeights(particles);
  // Spread = population std of {1, 2, 3} = sqrt(2/3); similarity exp(-(c - 1) / spread).
  const double spread = std::sqrt(2.0 / 3.0);
  const double s1 = std::exp(-1.0 / spread);
  const double s2 = std::exp(-2.0 / spread);
  const double total = 1.0 + s1 + s2;
  EXPECT_NEAR(particles[0].weight, 1.0 / total, 1e-9);
  EXPECT_NEAR(particles[1].weight, s1 / total, 1e-9);
  EXPECT_NEAR(particles[2].weight, s2 / total, 1e-9);
  EXPECT_NEAR(weightSum(particles), 1.0, 1e-12);
}

TEST(UpdateWeights, MultipliesThePriorWeights) {
  // Equal costs leave the (renormalised) prior unchanged.
  std::vector<Particle> particles{particle(0, 2.0, 5.0F), particle(1, 6.0, 5.0F)};
  updateWeights(particles);
  EXPECT_NEAR(particles[0].weight, 0.25, 1e-12);
  EXPECT_NEAR(particles[1].weight, 0.75, 1e-12);
}

TEST(UpdateWeights, IsInvariantToTheScaleOfTheCosts) {
  std::vector<Particle> a{particle(0, 0.5, 1.0F), particle(1, 0.5, 2.0F)};
  std::vector<Particle> b{particle(0, 0.5, 100.0F), particle(1, 0.5, 200.0F)};
  updateWeights(a);
  updateWeights(b);
  EXPECT_NEAR(a[0].weight, b[0].weight, 1e-9);
  EXPECT_GT(a[0].weight, a[1].weight);
  EXPECT_GT(a[1].weight, 0.0);  // Does not saturate.
  std::vector<Particle> none;
  EXPECT_NO_THROW(updateWeights(none));
}

TEST(EffectiveSampleSize, UniformIsTheCountOneHotIsOne) {
  std::vector<Particle> uniform;
  for (int i = 0; i < 8; ++i) uniform.push_back(particle(i, 1.0 / 8));
  EXPECT_NEAR(effectiveSampleSize(uniform), 8.0, 1e-12);
  std::vector<Particle> one_hot{particle(0, 0.0), particle(1, 1.0), particle(2, 0.0)};
  EXPECT_NEAR(effectiveSampleSize(one_hot), 1.0, 1e-12);
  std::vector<Particle> halves{particle(0, 0.5), particle(1, 0.5), particle(2, 0.0)};
  EXPECT_NEAR(effectiveSampleSize(halves), 2.0, 1e-12);
  EXPECT_EQ(effectiveSampleSize({}), 0.0);
}

TEST(ResampleSystematic, CopiesInProportionToWeightWithoutJitter) {
  std::vector<Particle> particles{particle(10, 0.5), particle(20, 0.25), particle(30, 0.25), particle(40, 0.0)};
  std::mt19937_64 rng(1);
  resampleSystematic(particles, 0, 0, 100, rng);
  ASSERT_EQ(particles.size(), 4U);
  std::map<int, int> copies;
  for (const Particle& p : particles) {
    ++copies[p.index];
    EXPECT_DOUBLE_EQ(p.weight, 0.25);
  }
  EXPECT_EQ(copies[10], 2);
  EXPECT_EQ(copies[20], 1);
  EXPECT_EQ(copies[30], 1);
  EXPECT_EQ(copies.count(40), 0U);
}

TEST(ResampleSystematic, IsDeterministicForASeedAndStaysWithinBounds) {
  std::vector<Particle> start;
  for (int i = 0; i < 20; ++i) start.push_back(particle(i * 5, (i % 3 + 1) / 40.0));
  std::vector<Particle> a = start;
  std::vector<Particle> b = start;
  std::mt19937_64 rng_a(99);
  std::mt19937_64 rng_b(99);
  resampleSystematic(a, 7, 3, 90, rng_a);
  resampleSystematic(b, 7, 3, 90, rng_b);
  ASSERT_EQ(a.size(), start.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].index, b[i].index) << i;
    EXPECT_GE(a[i].index, 3);
    EXPECT_LE(a[i].index, 90);
  }
  EXPECT_NEAR(weightSum(a), 1.0, 1e-12);
}

TEST(ResampleSystematic, OneHeavyParticleIsCopiedWithJitterAroundIt) {
  std::vector<Particle> particles{particle(5, 0.0), particle(50, 1.0), particle(95, 0.0)};
  std::mt19937_64 rng(4);
  resampleSystematic(particles, 3, 0, 100, rng);
  for (const Particle& p : particles) {
    EXPECT_GE(p.index, 47);
    EXPECT_LE(p.index, 53);
  }
}

TEST(Coverage, CountsTheUnionOfTheWindows) {
  EXPECT_EQ(coverage({}, 2), 0);
  EXPECT_EQ(coverage({particle(10, 1.0)}, 2), 5);
  // [8, 12] and [10, 14] overlap: [8, 14].
  EXPECT_EQ(coverage({particle(12, 0.5), particle(10, 0.5)}, 2), 7);
  // Disjoint windows add up; a duplicate adds nothing; a window inside another adds nothing.
  EXPECT_EQ(coverage({particle(0, 0.5), particle(100, 0.5)}, 1), 6);
  EXPECT_EQ(coverage({particle(7, 0.5), particle(7, 0.5)}, 3), 7);
  EXPECT_EQ(coverage({particle(20, 0.3), particle(21, 0.3), particle(40, 0.4)}, 0), 3);
  // Touching windows [0, 2] and [3, 5].
  EXPECT_EQ(coverage({particle(1, 0.5), particle(4, 0.5)}, 1), 6);
}

}  // namespace
}  // namespace mrs_vpr
