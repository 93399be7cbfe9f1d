#pragma once

#include <random>
#include <vector>

namespace mrs_vpr {

/// A hypothesis of MRS-VPR: where the test sequence ends in the current level's reference grid.
struct Particle {
  int index = 0;          ///< End index in level coordinates (reference frame = index * stride).
  double weight = 0.0;    ///< Normalised importance weight.
  float cost = 0.0F;      ///< Best mean difference found at `index` by the last evaluation.
  float velocity = 1.0F;  ///< Velocity of that best trajectory (reference frames per test frame).
};

/**
 * Multiplies every weight by a similarity exp(-(cost - min cost) / spread), spread = the standard
 * deviation of the costs. The paper's 1 / (1 + exp(-score)) rewards a larger difference; this
 * rewards a smaller one, and measuring it relative to the spread keeps it from saturating whatever the
 * level or scale of the costs. Weights are then normalised to sum to 1.
 */
void updateWeights(std::vector<Particle>& particles);

/// Effective sample size 1 / sum(w^2) of normalised weights.
double effectiveSampleSize(const std::vector<Particle>& particles);

/**
 * Systematic (low-variance) resampling: draws particles.size() particles in proportion to weight,
 * keeps the first copy of each drawn particle in place and moves every further copy by a uniform
 * jitter in [-jitter, jitter] clamped to [low, high], resets weights to uniform. The paper's
 * "resample around effective particles", made explicit.
 */
void resampleSystematic(std::vector<Particle>& particles, int jitter, int low, int high, std::mt19937_64& rng);

/// Number of distinct indices covered by the windows [index - radius, index + radius] of the particles.
int coverage(const std::vector<Particle>& particles, int radius);

}  // namespace mrs_vpr
