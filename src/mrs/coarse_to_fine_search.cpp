#include "mrs_vpr/mrs/coarse_to_fine_search.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include <opencv2/core/utility.hpp>

#include "mrs_vpr/acceptance.hpp"
#include "mrs_vpr/contrast_enhancement.hpp"
#include "mrs_vpr/difference_matrix.hpp"
#include "mrs_vpr/mrs/lazy_difference_matrix.hpp"
#include "mrs_vpr/mrs/particle_evaluation.hpp"
#include "mrs_vpr/mrs/particle_filter.hpp"
#include "mrs_vpr/mrs/sampling_level.hpp"
#include "mrs_vpr/mrs/tiled_end_costs.hpp"

namespace mrs_vpr {

int hypothesisSeparation(const SequenceParams& sequence, const MrsParams& mrs, int levels) {
  return std::max(2 * mrs.index_shift + 1, sequence.match_exclusion / (1 << levels));
}

int rivalExclusion(const SequenceParams& sequence, const MrsParams& mrs, int levels) {
  return levels == 0 ? sequence.match_exclusion : 2 * hypothesisSeparation(sequence, mrs, levels);
}

namespace {

/// One query of MRS-VPR (Algorithm 1 of the paper), its state kept between the steps.
class CoarseToFineSearch {
 public:
  CoarseToFineSearch(SequenceView reference, SequenceView query, const SequenceRows& rows, int levels,
                     const SequenceParams& sequence, const MrsParams& mrs, const CompactCells& compact,
                     const QueryStop* stop, const PlaceLinks* links)
      : reference_(reference), query_(query), rows_(rows), levels_(levels), sequence_(sequence), mrs_(mrs),
        compact_(compact), stop_(stop), links_(links),
        velocities_(velocities(sequence)), rng_(mrs.seed) {}

  Match run(std::vector<MrsLevelTrace>* trace) {
    level_ = SamplingLevel::make(coarseStride(), rows_, reference_.count, velocities_.front());
    if (level_.empty()) return result_;  // No trajectory fits in the reference.
    scoreCoarsestLevel();
    spreadParticles();
    for (int level_number = 0; level_number <= levels_ && !particles_.empty(); ++level_number) {
      iterateLevel(level_number == 0, level_number == 1, level_number == levels_);
      if (trace != nullptr) trace->push_back(traceLevel(level_number == 0));
      if (level_number < levels_) descend(level_number == 0);
    }
    return finish();
  }

 private:
  /// The coarsest level. Uniformly spread particles with their +-Id_shift windows, velocity fans
  /// and contrast windows would touch nearly every cell of it anyway, so its matrix is computed
  /// densely (vectorised, on compact cells), a tile at a time, and every end is
  /// scored once; particles then read the table. The table also gives the runner-up for the
  /// confidence. At full resolution (no coarser level) it is the brute force's table.
  void scoreCoarsestLevel() {
    DescriptorSequence query_cells(1);
    const SequenceView cells = levelQuery(query_cells);
    if (level_.stride == 1) {
      // No coarser level: the brute force's own dense search, so that the answers are its answers.
      cv::Mat matrix(cells.count, reference_.count, CV_32F);
      computeDifferenceMatrix(cells, reference_, matrix, stop_);
      result_.comparisons += static_cast<long long>(matrix.total());
      enhanceContrastInPlace(matrix, sequence_.contrast_window, stop_);
      coarse_costs_ =
          std::make_unique<EndCostTable>(costsByAnchor(matrix, level_.sequenceRows(), velocities_, stop_), level_);
      return;
    }
    std::atomic<long long> compared{0};
    const auto tile = [&](int begin, int end, cv::Mat& raw) {
      // The grid's cells from those the store keeps (complete cells only: below grid_size).
      cellDifferences(cells, reference_, level_.stride, level_.grid_size, compact_, begin, end, raw);
      compared.fetch_add(static_cast<long long>(raw.total()), std::memory_order_relaxed);
    };
    coarse_costs_ = std::make_unique<EndCostTable>(
        tiledCostsByAnchor(level_.grid_size, level_.sequenceRows(), velocities_, sequence_.contrast_window, tile,
                           stop_),
        level_);
    result_.comparisons += std::llround(static_cast<double>(compared.load()) * cellShare());
  }

  /// Comparisons are counted in descriptor comparisons: a cell costs this share of one.
  double cellShare() const {
    return level_.stride == 1 ? 1.0 : static_cast<double>(compact_.cellSize()) / compact_.descriptorSize();
  }

  /// The test sequence at the current level, row k - k_min ending at frame anchor + k * stride:
  /// the frames themselves at full resolution, else cells computed into `storage`.
  SequenceView levelQuery(DescriptorSequence& storage) const {
    if (level_.stride == 1) return query_.slice(rows_.first, rows_.last + 1);
    storage = compact_.cells(query_, rows_.anchor + level_.k_min * level_.stride, level_.stride, level_.rows());
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

  /**
   * The coarsest level runs the paper's loop: evaluate, weight, resample until the coverage shrinks
   * or nothing changes. Below it the particles are distinct hypotheses that each settle on the best
   * end near them with a velocity fan of their own; none is resampled away, so that the level below
   * the coarsest (`comparing`) can decide among them with contrast-enhanced costs, the only ones
   * that compare places far apart fairly. Deeper levels only localise the winner, on raw
   * differences: ends a few frames apart have nearly the same local contrast statistics, so
   * enhancement would not change their order but would cost window/2 extra cells on either side.
   */
  void iterateLevel(bool coarsest, bool comparing, bool finest) {
    if (coarsest) {
      iterateParticleFilter(*coarse_costs_, finest);  // Its table is already complete.
    } else {
      settleHypotheses(comparing, finest);
    }
    previous_rows_ = level_.rows();
  }

  /// Each hypothesis settles on the cells its own trajectories visit. Hypotheses are distinct places,
  /// more than a basin apart, so they share no cells: each has a lazy matrix of its own and they
  /// settle in parallel (OpenCV's threads). The best end is merged in hypothesis order, and a lone
  /// hypothesis sums its rows in order, so that the answer does not depend on the number of threads.
  void settleHypotheses(bool comparing, bool finest) {
    DescriptorSequence query_cells(1);
    const SequenceView cells = levelQuery(query_cells);
    const int count = static_cast<int>(particles_.size());
    std::vector<Evaluation> bests(particles_.size());
    std::vector<long long> comparisons(particles_.size(), 0);
    const auto settle_range = [&](const cv::Range& range) {
      for (int i = range.start; i < range.end; ++i) {
        Particle& particle = particles_[static_cast<std::size_t>(i)];
        LazyDifferenceMatrix matrix(cells, reference_, level_.stride, compact_,
                                    comparing ? sequence_.contrast_window : 0);
        EndCostTable costs(matrix, level_, levelVelocities(particle), level_.stride > 1);
        bests[static_cast<std::size_t>(i)] = settle(particle, costs);
        comparisons[static_cast<std::size_t>(i)] = matrix.comparisons();
      }
    };
    // A lone hypothesis (below the comparing level) shares its rows among the threads instead.
    if (count == 1) {
      settle_range(cv::Range(0, 1));
    } else {
      cv::parallel_for_(cv::Range(0, count), settle_range);
    }
    long long total = 0;
    for (int i = 0; i < count; ++i) {
      const Evaluation& best = bests[static_cast<std::size_t>(i)];
      if (finest && best.cost < best_.cost) best_ = best;
      total += comparisons[static_cast<std::size_t>(i)];
    }
    dropInfeasible();
    result_.comparisons += std::llround(static_cast<double>(total) * cellShare());
  }

  /// The paper's loop on the coarsest level's table.
  void iterateParticleFilter(EndCostTable& costs, bool finest) {
    bool resampled = false;
    for (int iteration = 0; iteration < mrs_.max_iterations; ++iteration) {
      const int coverage_before = coverage(particles_, mrs_.index_shift);
      const bool moved = moveParticles(costs, iteration == 0 ? first_radius_ : mrs_.index_shift, finest);
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
      // before the level ends.
      moveParticles(costs, mrs_.index_shift, finest);
      for (Particle& particle : particles_) particle.weight = 1.0 / static_cast<double>(particles_.size());
      updateWeights(particles_);
    }
  }

  /// Moves a hypothesis to the best end within +-Id_shift until it stays (at most max_iterations);
  /// returns the best end it saw.
  Evaluation settle(Particle& particle, EndCostTable& costs) const {
    Evaluation best;
    for (int iteration = 0; iteration < mrs_.max_iterations; ++iteration) {
      const Evaluation evaluation = costs.bestInWindow(particle.index, mrs_.index_shift);
      particle.cost = evaluation.cost;
      if (evaluation.index < 0) break;
      const bool moved = evaluation.index != particle.index;
      particle.index = evaluation.index;
      particle.velocity = evaluation.velocity;
      if (evaluation.cost < best.cost) best = evaluation;
      if (!moved) break;
    }
    return best;
  }

  /// Drops the particles where no trajectory fits (infinite cost): they carry no weight.
  void dropInfeasible() {
    particles_.erase(std::remove_if(particles_.begin(), particles_.end(),
                                    [](const Particle& p) { return !std::isfinite(p.cost); }),
                     particles_.end());
  }

  /// The level's hypotheses as reference frames, lowest cost first.
  MrsLevelTrace traceLevel(bool coarsest) const {
    MrsLevelTrace trace;
    trace.stride = level_.stride;
    std::vector<Particle> sorted = particles_;
    std::sort(sorted.begin(), sorted.end(), [](const Particle& a, const Particle& b) { return a.cost < b.cost; });
    for (const Particle& particle : sorted) trace.candidates.push_back(particle.index * level_.stride);
    if (coarsest) {
      const std::vector<int> minima =
          distinctMinima(coarse_costs_->costs(), hypothesisSeparation(), MrsLevelTrace::kTracedMinima);
      for (int index : minima) trace.table_minima.push_back(index * level_.stride);
      if (!minima.empty()) {
        trace.table_confidence =
            scoreAround(coarse_costs_->costs(), minima.front(), rivalExclusion(), links_, coarseStride()).confidence;
      }
    }
    return trace;
  }

  int rivalExclusion() const { return mrs_vpr::rivalExclusion(sequence_, mrs_, levels_); }
  /// The stride of the coarsest level, whose table scores every end of the map.
  int coarseStride() const { return 1 << levels_; }
  int hypothesisSeparation() const { return mrs_vpr::hypothesisSeparation(sequence_, mrs_, levels_); }

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
    dropInfeasible();
    return moved;
  }

  /// A hypothesis searches the velocities within fanSpread() of its own from the level above.
  std::vector<double> levelVelocities(const Particle& particle) const {
    const bool after_coarsest = 2 * level_.stride == coarseStride();
    const double spread = fanSpread(sequence_.velocity_step, previous_rows_, after_coarsest);
    return velocitiesNear(velocities_, particle.velocity, spread);
  }

  /**
   * Next level: half the stride, indices double. Leaving the coarsest level, the hypotheses are the
   * mrs/hypotheses lowest distinct minima of its table, where the particles have settled and where
   * any minimum they missed lies: the truth can rank below the first on a short coarse sequence,
   * and the level below, with twice the rows, tells them apart. Below that only the winner goes on.
   */
  void descend(bool from_coarsest) {
    if (from_coarsest) {
      const std::vector<float>& table = coarse_costs_->costs();
      particles_.clear();
      for (int index : distinctMinima(table, hypothesisSeparation(), mrs_.hypotheses)) {
        Particle particle;
        particle.index = index;
        particle.cost = table[static_cast<std::size_t>(index)];
        particle.velocity = coarse_costs_->velocityAt(index);
        particles_.push_back(particle);
      }
    } else {
      if (particles_.empty()) return;  // The run's loop ends there; no winner to take down.
      const auto winner = std::min_element(particles_.begin(), particles_.end(),
                                           [](const Particle& a, const Particle& b) { return a.cost < b.cost; });
      particles_ = {*winner};
    }
    for (Particle& particle : particles_) particle.weight = 1.0 / static_cast<double>(particles_.size());
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
    result_.velocity = best_.velocity;
    const int coarse_stride = coarseStride();
    const Match coarse =
        scoreAround(coarse_costs_->costs(), best_.index / coarse_stride, rivalExclusion(), links_, coarse_stride);
    result_.score = coarse.score;
    result_.confidence = coarse.confidence;
    result_.rivals = coarse.rivals;
    result_.rival_places = placesAmong(coarse.rivals, coarse_stride, sequence_.match_exclusion);
    applyAcceptance(result_, sequence_);
    return result_;
  }

  SequenceView reference_;
  SequenceView query_;
  SequenceRows rows_;
  int levels_;
  const SequenceParams& sequence_;
  const MrsParams& mrs_;
  const CompactCells& compact_;
  const QueryStop* stop_;
  const PlaceLinks* links_;
  std::vector<double> velocities_;
  std::mt19937_64 rng_;

  SamplingLevel level_;
  std::unique_ptr<EndCostTable> coarse_costs_;
  std::vector<Particle> particles_;
  int first_radius_ = 0;
  int previous_rows_ = 1;
  Evaluation best_;
  Match result_;
};

}  // namespace

Match coarseToFineSearch(SequenceView reference, SequenceView query, const SequenceRows& rows, int levels,
                         const SequenceParams& sequence, const MrsParams& mrs, const CompactCells& compact,
                         std::vector<MrsLevelTrace>* trace, const QueryStop* stop, const PlaceLinks* links) {
  return CoarseToFineSearch(reference, query, rows, levels, sequence, mrs, compact, stop, links).run(trace);
}

}  // namespace mrs_vpr
