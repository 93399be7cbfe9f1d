#include "mrs_vpr/mrs_search.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "mrs_vpr/acceptance.hpp"
#include "mrs_vpr/contrast_enhancement.hpp"
#include "mrs_vpr/difference_matrix.hpp"
#include "mrs_vpr/lazy_difference_matrix.hpp"
#include "mrs_vpr/particle_evaluation.hpp"
#include "mrs_vpr/particle_filter.hpp"
#include "mrs_vpr/sampling_level.hpp"
#include "mrs_vpr/temporal_pooling.hpp"
#include "mrs_vpr/trajectory_search.hpp"

namespace mrs_vpr {
namespace {

/// Differences between the test cells and the reference grid of a level. The grid's cells come
/// from the ones the reference's store keeps (complete cells only), the rest (all of them when it
/// keeps none, else the last, partial one) are pooled now.
cv::Mat levelDifferences(SequenceView query_cells, SequenceView reference, const SamplingLevel& level,
                         int pixel_pooling) {
  if (level.stride == 1) return computeDifferenceMatrix(query_cells, reference);  // Full resolution.
  cv::Mat differences(query_cells.count, level.grid_size, CV_32F);
  const SequenceView kept = reference.pooledCells(level.stride, pixel_pooling);
  const int known = std::min(kept.count, level.grid_size);
  if (known > 0) {
    cv::Mat columns = differences.colRange(0, known);
    computeDifferenceMatrix(query_cells, kept.slice(0, known), columns);
  }
  if (known < level.grid_size) {
    const DescriptorSequence pooled =
        poolSequence(reference, known * level.stride, level.stride, level.grid_size - known, pixel_pooling);
    cv::Mat columns = differences.colRange(known, level.grid_size);
    computeDifferenceMatrix(query_cells, pooled.view(), columns);
  }
  return differences;
}

/// One query of MRS-VPR (Algorithm 1 of the paper), its state kept between the steps.
class CoarseToFineSearch {
 public:
  CoarseToFineSearch(SequenceView reference, SequenceView query, const SequenceRows& rows, int levels,
                     const SequenceParams& sequence, const MrsParams& mrs)
      : reference_(reference), query_(query), rows_(rows), levels_(levels), sequence_(sequence), mrs_(mrs),
        velocities_(velocities(sequence)), rng_(mrs.seed),
        query_runs_(levels > 0 ? query : SequenceView{}, mrs.pixel_pooling) {}

  Match run() {
    level_ = SamplingLevel::make(1 << levels_, rows_, reference_.count, velocities_.front());
    if (level_.empty()) return result_;  // No trajectory fits in the reference.
    scoreCoarsestLevel();
    spreadParticles();
    for (int level_number = 0; level_number <= levels_ && !particles_.empty(); ++level_number) {
      iterateLevel(level_number == 0, level_number == levels_);
      if (level_number < levels_) descend();
    }
    return finish();
  }

 private:
  /// The coarsest level. Uniformly spread particles with their +-Id_shift windows, velocity fans
  /// and contrast windows would touch nearly every cell of it anyway, so its matrix is computed
  /// densely (vectorised, on pooled cells) and every end is scored once; particles then read the
  /// table. The table also gives the runner-up for the confidence.
  void scoreCoarsestLevel() {
    const int pixel_pooling = level_.pixelPooling(mrs_.pixel_pooling);
    DescriptorSequence query_cells(1);
    const cv::Mat matrix = enhanceContrast(
        levelDifferences(levelQuery(query_cells), reference_, level_, pixel_pooling), sequence_.contrast_window);
    result_.comparisons += static_cast<long long>(matrix.total()) / pixel_pooling;
    coarse_costs_ = std::make_unique<EndCostTable>(costsByAnchor(matrix, level_.sequenceRows(), velocities_), level_);
  }

  /// The test sequence at the current level, row k - k_min ending at frame anchor + k * stride:
  /// the frames themselves at full resolution, else cells pooled into `storage`.
  SequenceView levelQuery(DescriptorSequence& storage) const {
    if (level_.stride == 1) return query_.slice(rows_.first, rows_.last + 1);
    storage = query_runs_.pool(rows_.anchor + level_.k_min * level_.stride, level_.stride, level_.rows());
    return storage.view();
  }

  /// P_init = (M / N) * tau particles, uniformly over the ends that fit.
  void spreadParticles() {
    const int count = std::max(mrs_.min_particles,
                               static_cast<int>(std::lround(static_cast<double>(reference_.count) / query_.count *
                                                            mrs_.tau)));
    const int span = level_.highest_end - level_.lowest_end + 1;
    particles_.resize(static_cast<std::size_t>(count));
    for (int i = 0; i < count; ++i) {
      Particle& particle = particles_[static_cast<std::size_t>(i)];
      particle.index = level_.lowest_end + static_cast<int>((i + 0.5) * span / count);
      particle.weight = 1.0 / count;
    }
    // The first look gives each particle its share of the map, so that together they see every
    // coarse end once; later looks search +-Id_shift around where a particle has moved to.
    first_radius_ = std::max(mrs_.index_shift, (span + count) / (2 * count));
  }

  /// Evaluate, weight, resample until the coverage shrinks (the paper's loop) or nothing changes.
  void iterateLevel(bool coarsest, bool finest) {
    const int pixel_pooling = level_.pixelPooling(mrs_.pixel_pooling);
    DescriptorSequence query_cells(1);
    const SequenceView query_rows = coarsest ? SequenceView{} : levelQuery(query_cells);
    // Finer levels compare ends a few frames apart, whose local contrast statistics are nearly the
    // same: enhancement would not change their order but would cost window/2 extra cells on each
    // side of every cell. Raw differences are used there (same success on Nordland, measured).
    LazyDifferenceMatrix matrix(query_rows, reference_, level_.stride, pixel_pooling, 0);
    std::unique_ptr<EndCostTable> lazy_costs;
    if (!coarsest) lazy_costs = std::make_unique<EndCostTable>(matrix, level_, levelVelocities());
    EndCostTable& costs = coarsest ? *coarse_costs_ : *lazy_costs;

    bool resampled = false;
    for (int iteration = 0; iteration < mrs_.max_iterations; ++iteration) {
      const int coverage_before = coverage(particles_, mrs_.index_shift);
      const bool moved =
          moveParticles(costs, coarsest && iteration == 0 ? first_radius_ : mrs_.index_shift, finest);
      if (particles_.empty()) break;
      updateWeights(particles_);
      resampled = effectiveSampleSize(particles_) < mrs_.resample_threshold * static_cast<double>(particles_.size());
      if (resampled) {
        resampleSystematic(particles_, 2 * mrs_.index_shift, level_.lowest_end, level_.highest_end, rng_);
      }
      // The paper's rule: stay on a level until the map coverage shrinks below the threshold.
      if (coverage(particles_, mrs_.index_shift) < mrs_.coverage_threshold * coverage_before) break;
      if (!moved && !resampled) break;  // Converged: another pass would evaluate the same cells.
    }
    if (resampled && !particles_.empty()) {
      // Resampling jittered the particles away from the ends their costs belong to; let them settle
      // on this level before the heaviest are chosen, or the ranking would go by stale costs.
      moveParticles(costs, mrs_.index_shift, finest);
      for (Particle& particle : particles_) particle.weight = 1.0 / static_cast<double>(particles_.size());
      updateWeights(particles_);
    }
    result_.comparisons += matrix.comparisons() / pixel_pooling;
    previous_rows_ = level_.rows();
  }

  /// Algorithm 2 for every particle: move to the best end within `radius`. Particles where no
  /// trajectory fits are dropped (they carry no weight). Returns whether any particle moved.
  bool moveParticles(EndCostTable& costs, int radius, bool finest) {
    bool moved = false;
    for (Particle& particle : particles_) {
      const Evaluation evaluation = costs.bestInWindow(particle.index, radius);
      particle.cost = evaluation.cost;
      if (evaluation.index < 0) continue;
      moved = moved || evaluation.index != particle.index;
      particle.index = evaluation.index;
      particle.velocity = evaluation.velocity;
      if (finest && evaluation.cost < best_.cost) best_ = evaluation;
    }
    particles_.erase(std::remove_if(particles_.begin(), particles_.end(),
                                    [](const Particle& p) { return !std::isfinite(p.cost); }),
                     particles_.end());
    return moved;
  }

  /// A finer level searches the velocities within fanSpread() of the heaviest particle's on the
  /// previous level. Around every particle's own velocity instead, the union is wider and costs 15%
  /// more time for the same success (measured).
  std::vector<double> levelVelocities() const {
    const bool after_coarsest = 2 * level_.stride == (1 << levels_);
    const double spread = fanSpread(sequence_.velocity_step, previous_rows_, after_coarsest);
    const auto heaviest = std::max_element(particles_.begin(), particles_.end(),
                                           [](const Particle& a, const Particle& b) { return a.weight < b.weight; });
    return velocitiesNear(velocities_, heaviest->velocity, spread);
  }

  /// Next level: half the stride, indices double, fewer particles survive (N_eff of them, at most
  /// half, at least min_particles).
  void descend() {
    const int half = std::max(mrs_.min_particles, (static_cast<int>(particles_.size()) + 1) / 2);
    const int survivors =
        std::clamp(static_cast<int>(std::ceil(effectiveSampleSize(particles_))), mrs_.min_particles, half);
    keepHeaviest(particles_, survivors);
    level_ = SamplingLevel::make(level_.stride / 2, rows_, reference_.count, velocities_.front());
    for (Particle& particle : particles_) {
      particle.index = std::clamp(particle.index * 2, level_.lowest_end, level_.highest_end);
    }
  }

  /// The best end seen at full resolution. Its confidence is read on the coarse table, the one level
  /// that scores every end of the map: the answer's coarse cell against its best rival there.
  Match finish() {
    if (best_.index < 0) return result_;
    result_.reference_index = best_.index;
    result_.sequence_difference = best_.cost;
    const int coarse_stride = 1 << levels_;
    const Match coarse = scoreAround(coarse_costs_->costs(), best_.index / coarse_stride,
                                     std::max(2, sequence_.match_exclusion / coarse_stride));
    result_.score = coarse.score;
    result_.confidence = coarse.confidence;
    applyAcceptance(result_, sequence_.accept_threshold);
    return result_;
  }

  SequenceView reference_;
  SequenceView query_;
  SequenceRows rows_;
  int levels_;
  const SequenceParams& sequence_;
  const MrsParams& mrs_;
  std::vector<double> velocities_;
  std::mt19937_64 rng_;
  PixelRunSums query_runs_;  ///< Pools the test sequence at every level below full resolution.

  SamplingLevel level_;
  std::unique_ptr<EndCostTable> coarse_costs_;
  std::vector<Particle> particles_;
  int first_radius_ = 0;
  int previous_rows_ = 1;
  Evaluation best_;
  Match result_;
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
  if (reference.descriptor_size % mrs_.pixel_pooling != 0) {
    throw std::invalid_argument("mrs/pixel_pooling " + std::to_string(mrs_.pixel_pooling) +
                                " does not divide the descriptor size " + std::to_string(reference.descriptor_size));
  }
  return CoarseToFineSearch(reference, query, wholeSequenceRows(query.count, sequence_.alignment),
                            levelsFor(query.count), sequence_, mrs_)
      .run();
}

}  // namespace mrs_vpr
