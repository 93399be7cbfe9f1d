#include "mrs_vpr/mrs_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "mrs_vpr/lazy_difference_matrix.hpp"
#include "mrs_vpr/particle_filter.hpp"
#include "mrs_vpr/trajectory_search.hpp"

namespace mrs_vpr {
namespace {

constexpr float kNoCost = std::numeric_limits<float>::infinity();

/// One sampling level: stride, the test frames it sees (k_min..k_max around the anchor), and the
/// end indices whose trajectories can fit in its reference grid.
struct Level {
  int stride = 1;
  int k_min = 0;
  int k_max = 0;
  int lowest_end = 0;
  int highest_end = 0;
};

Level makeLevel(int stride, const SequenceRows& rows, int grid_size, double velocity_min) {
  Level level;
  level.stride = stride;
  level.k_min = -((rows.anchor - rows.first) / stride);
  level.k_max = (rows.last - rows.anchor) / stride;
  // The slowest velocity reaches least far, so it bounds where any trajectory can end.
  level.lowest_end = static_cast<int>(std::lround(velocity_min * -level.k_min));
  level.highest_end = grid_size - 1 - static_cast<int>(std::lround(velocity_min * level.k_max));
  return level;
}

/// The best end index within `radius` of `centre` and its cost (mean enhanced difference along the
/// best straight trajectory): Algorithm 2 of the paper.
struct Evaluation {
  int index = -1;
  float cost = kNoCost;
};

class ParticleEvaluator {
 public:
  ParticleEvaluator(LazyDifferenceMatrix& differences, const std::vector<double>& velocities)
      : differences_(differences), velocities_(velocities) {}

  /// Cost of the trajectory ending at `end` with `velocity`; kNoCost when it leaves the grid.
  float trajectoryCost(const Level& level, int end, double velocity) {
    const int oldest = end + static_cast<int>(std::lround(velocity * level.k_min));
    const int newest = end + static_cast<int>(std::lround(velocity * level.k_max));
    if (oldest < 0 || newest >= differences_.gridSize()) return kNoCost;
    float sum = 0.0F;
    for (int k = level.k_min; k <= level.k_max; ++k) {
      sum += differences_.enhanced(k, end + static_cast<int>(std::lround(velocity * k)));
    }
    return sum / static_cast<float>(level.k_max - level.k_min + 1);
  }

  float endCost(const Level& level, int end) {
    float best = kNoCost;
    for (double velocity : velocities_) best = std::min(best, trajectoryCost(level, end, velocity));
    return best;
  }

  Evaluation evaluate(const Level& level, int centre, int radius, std::vector<float>* costs_by_end) {
    Evaluation best;
    const int begin = std::max(level.lowest_end, centre - radius);
    const int end = std::min(level.highest_end, centre + radius);
    for (int index = begin; index <= end; ++index) {
      const float cost = endCost(level, index);
      if (costs_by_end != nullptr) (*costs_by_end)[static_cast<std::size_t>(index)] = cost;
      if (cost < best.cost) best = {index, cost};
    }
    return best;
  }

 private:
  LazyDifferenceMatrix& differences_;
  const std::vector<double>& velocities_;
};

}  // namespace

MrsSearch::MrsSearch(const SequenceParams& sequence, const MrsParams& mrs) : SequenceMatcher(sequence), mrs_(mrs) {
  mrs_.validate();
}

int MrsSearch::levelsFor(int query_length) const {
  // The paper's l_max = 4 failed with ~19 coarse frames: never let the coarsest level get too short.
  int levels = mrs_.levels;
  while (levels > 0 && (query_length - 1) / (1 << levels) + 1 < mrs_.min_coarse_frames) --levels;
  return levels;
}

Match MrsSearch::match(SequenceView reference, SequenceView query) const {
  checkInputs(reference, query);
  SequenceRows rows;
  rows.first = 0;
  rows.last = query.count - 1;
  rows.anchor = sequence_.alignment == WindowAlignment::kCausal ? rows.last : rows.last / 2;

  const int levels = levelsFor(query.count);
  const std::vector<double> speeds = velocities(sequence_);
  LazyDifferenceMatrix differences(query, reference, sequence_.contrast_window);
  ParticleEvaluator evaluator(differences, speeds);
  std::mt19937_64 rng(mrs_.seed);

  // P_init = (M / N) * tau particles, spread uniformly over the coarsest grid.
  const int coarsest_stride = 1 << levels;
  differences.setLevel(coarsest_stride, rows.anchor);
  Level level = makeLevel(coarsest_stride, rows, differences.gridSize(), speeds.front());
  if (level.lowest_end > level.highest_end) {
    // The reference is too short for the coarse level; nothing to search.
    Match none;
    none.comparisons = differences.comparisons();
    return none;
  }
  const int particle_count = std::max(
      mrs_.min_particles,
      static_cast<int>(std::lround(static_cast<double>(reference.count) / query.count * mrs_.tau)));
  const int span = level.highest_end - level.lowest_end + 1;
  std::vector<Particle> particles(static_cast<std::size_t>(particle_count));
  for (int i = 0; i < particle_count; ++i) {
    particles[static_cast<std::size_t>(i)].index =
        level.lowest_end + static_cast<int>((i + 0.5) * span / particle_count);
    particles[static_cast<std::size_t>(i)].weight = 1.0 / particle_count;
  }

  // Every cost seen on the coarsest grid, for the runner-up of the confidence.
  std::vector<float> coarse_costs(static_cast<std::size_t>(differences.gridSize()), kNoCost);
  Evaluation best_final;

  for (int level_number = 0; level_number <= levels; ++level_number) {
    const bool coarsest = level_number == 0;
    const bool finest = level_number == levels;
    for (int iteration = 0; iteration < mrs_.max_iterations; ++iteration) {
      const int coverage_before = coverage(particles, mrs_.index_shift);
      bool moved = false;
      for (Particle& particle : particles) {
        const Evaluation evaluation =
            evaluator.evaluate(level, particle.index, mrs_.index_shift, coarsest ? &coarse_costs : nullptr);
        if (evaluation.index < 0) {
          particle.cost = kNoCost;
          continue;
        }
        moved = moved || evaluation.index != particle.index;
        particle.index = evaluation.index;
        particle.cost = evaluation.cost;
        if (finest && evaluation.cost < best_final.cost) best_final = evaluation;
      }
      // Particles stranded where no trajectory fits carry no weight.
      particles.erase(std::remove_if(particles.begin(), particles.end(),
                                     [](const Particle& p) { return !std::isfinite(p.cost); }),
                      particles.end());
      if (particles.empty()) break;
      updateWeights(particles);
      bool resampled = false;
      if (effectiveSampleSize(particles) < mrs_.resample_threshold * static_cast<double>(particles.size())) {
        resampleSystematic(particles, 2 * mrs_.index_shift, level.lowest_end, level.highest_end, rng);
        resampled = true;
      }
      // Paper: stay on a level while the map coverage shrinks by less than the threshold.
      const int coverage_after = coverage(particles, mrs_.index_shift);
      if (coverage_after < mrs_.coverage_threshold * coverage_before) break;
      if (!moved && !resampled) break;  // Converged: another pass would evaluate the same cells.
    }
    if (particles.empty() || finest) break;

    // Next level: half the stride, indices double, fewer particles survive.
    const int stride = level.stride / 2;
    differences.setLevel(stride, rows.anchor);
    level = makeLevel(stride, rows, differences.gridSize(), speeds.front());
    keepHeaviest(particles, std::max(mrs_.min_particles, (static_cast<int>(particles.size()) + 1) / 2));
    for (Particle& particle : particles) {
      particle.index = std::clamp(particle.index * 2, level.lowest_end, level.highest_end);
    }
  }

  Match match;
  match.comparisons = differences.comparisons();
  if (best_final.index < 0) return match;
  match.reference_index = best_final.index;
  match.sequence_difference = best_final.cost;

  // Confidence: OpenSeqSLAM's best / runner-up ratio, on the coarsest grid where the particles
  // started spread over the whole map.
  const Match coarse = scoreFromCosts(coarse_costs, std::max(2, sequence_.match_exclusion / coarsest_stride));
  match.score = coarse.score;
  match.confidence = coarse.confidence;
  return match;
}

}  // namespace mrs_vpr
