#include "mrs_vpr/mrs/particle_filter.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

namespace mrs_vpr {
namespace {

Eigen::VectorXd weightsOf(const std::vector<Particle>& particles) {
  Eigen::VectorXd weights(static_cast<Eigen::Index>(particles.size()));
  for (std::size_t i = 0; i < particles.size(); ++i) weights[static_cast<Eigen::Index>(i)] = particles[i].weight;
  return weights;
}

void setWeights(std::vector<Particle>& particles, const Eigen::VectorXd& weights) {
  const double total = weights.sum();
  for (std::size_t i = 0; i < particles.size(); ++i) {
    particles[i].weight = total > 0.0 ? weights[static_cast<Eigen::Index>(i)] / total
                                      : 1.0 / static_cast<double>(particles.size());
  }
}

}  // namespace

void updateWeights(std::vector<Particle>& particles) {
  if (particles.empty()) return;
  const auto count = static_cast<Eigen::Index>(particles.size());
  Eigen::VectorXd costs(count);
  for (Eigen::Index i = 0; i < count; ++i) costs[i] = particles[static_cast<std::size_t>(i)].cost;
  const double mean = costs.mean();
  const double spread = std::max(1e-3, std::sqrt((costs.array() - mean).square().mean()));
  const Eigen::VectorXd similarity = (-(costs.array() - costs.minCoeff()) / spread).exp();
  setWeights(particles, weightsOf(particles).cwiseProduct(similarity));
}

double effectiveSampleSize(const std::vector<Particle>& particles) {
  const double sum_of_squares = weightsOf(particles).squaredNorm();
  return sum_of_squares > 0.0 ? 1.0 / sum_of_squares : 0.0;
}

void resampleSystematic(std::vector<Particle>& particles, int jitter, int low, int high, std::mt19937_64& rng) {
  const std::size_t count = particles.size();
  if (count == 0) return;
  std::uniform_real_distribution<double> start(0.0, 1.0 / static_cast<double>(count));
  std::uniform_int_distribution<int> move(-jitter, jitter);
  std::vector<Particle> drawn;
  drawn.reserve(count);
  double pointer = start(rng);
  double cumulative = particles.front().weight;
  std::size_t source = 0;
  std::size_t previous_source = count;  // None yet.
  for (std::size_t i = 0; i < count; ++i) {
    while (pointer > cumulative && source + 1 < count) cumulative += particles[++source].weight;
    Particle copy = particles[source];
    // The first copy of a particle stays where it is, only further copies explore around it: on a
    // sharp cost landscape (a fine level, where only the exact end matches) jittering every copy
    // would lose the best particle.
    const int jitter_here = source == previous_source ? move(rng) : 0;
    copy.index = std::clamp(copy.index + jitter_here, low, high);
    previous_source = source;
    copy.weight = 1.0 / static_cast<double>(count);
    drawn.push_back(copy);
    pointer += 1.0 / static_cast<double>(count);
  }
  particles.swap(drawn);
}

int coverage(const std::vector<Particle>& particles, int radius) {
  std::vector<int> indices;
  indices.reserve(particles.size());
  for (const Particle& particle : particles) indices.push_back(particle.index);
  std::sort(indices.begin(), indices.end());
  int covered = 0;
  int covered_until = 0;  // Exclusive end of the union so far.
  bool first = true;
  for (int index : indices) {
    const int begin = index - radius;
    const int end = index + radius + 1;
    if (first || begin >= covered_until) {
      covered += end - begin;
    } else if (end > covered_until) {
      covered += end - covered_until;
    }
    covered_until = first ? end : std::max(covered_until, end);
    first = false;
  }
  return covered;
}

}  // namespace mrs_vpr
