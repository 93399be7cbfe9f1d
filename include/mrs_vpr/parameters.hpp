#pragma once

#include <cstdint>
#include <string>

namespace mrs_vpr {

/// Image pre-processing (OpenSeqSLAM front end). Defaults are OpenSeqSLAM's.
struct DescriptorParams {
  int image_width = 64;  ///< Width after resizing [px], 4..1024.
  int image_height = 32; ///< Height after resizing [px], 4..1024.
  int patch_size = 8;    ///< Side of the normalisation patches [px]; divides width and height.

  /// Throws std::invalid_argument naming the first parameter out of range.
  void validate() const;
};

/// Where the test sequence sits relative to the query frame it localises.
enum class WindowAlignment {
  kCausal,  ///< The sequence ends at the query frame (what a live robot has).
  kCentred, ///< The query frame is in the middle of the sequence (OpenSeqSLAM).
};

/// Velocities a search may try: each one costs a pass over the difference matrix, and a step so fine
/// that their count overflows would crash a search rather than just slow it.
constexpr int kMaxVelocities = 1000;

/// Sequence matching shared by brute-force SeqSLAM and MRS-VPR. Defaults are OpenSeqSLAM's.
struct SequenceParams {
  int sequence_length = 10;    ///< ds: frames per test sequence in the per-frame protocol, 2..10000.
  double velocity_min = 0.8;   ///< Slowest reference frames per test frame, (0, velocity_max].
  double velocity_max = 1.2;   ///< Fastest reference frames per test frame, [velocity_min, 10].
  double velocity_step = 0.1;  ///< Step between tried velocities, (0, 10); at most kMaxVelocities of them.
  int contrast_window = 10;    ///< R: reference frames in the local contrast window, 0 (off) or 2..1000.
  int match_exclusion = 10;    ///< Rwindow: frames around the best match excluded from the runner-up, 0..10000.
  WindowAlignment alignment = WindowAlignment::kCausal;
  /// An answer is accepted as a loop closure when its confidence (distinctiveness, in standard
  /// deviations of the query's own end costs) reaches this, 0..1000. 3 is a three-sigma rule, not a
  /// value fitted to a data set; see acceptance.hpp for its derivation and the README for checks.
  double accept_threshold = 3.0;

  void validate() const;
};

/// The coarse-to-fine particle search of MRS-VPR. Defaults follow the paper where it gives one.
struct MrsParams {
  int levels = 3;               ///< l_max: the coarsest stride is 2^levels, 0..8.
  /// Fewer levels are used when N / 2^levels would drop below this, 2..1000. Below about 64 coarse
  /// rows the true place is too often not the coarse level's first minimum (README).
  int min_coarse_frames = 64;
  double tau = 2.0;             ///< Particle overlap factor, P_init = (M / N) * tau, 1..16.
  /// Levels coarser than full resolution average runs of this many pixels, 1..64. 16 is 1.6x faster
  /// at N = 300 but its coarse table sometimes ranks a wrong place first at an accepted confidence,
  /// which the finer levels then have to catch; 4 never did (README).
  int pixel_pooling = 4;
  int index_shift = 2;          ///< Id_shift: end-index search radius of a particle, in level frames, 0..1000.
  double coverage_threshold = 0.5;  ///< Go to the next level once coverage shrinks below this ratio, (0, 1).
  int max_iterations = 8;           ///< Cap on particle iterations per level (the paper has none), 1..1000.
  double resample_threshold = 0.5;  ///< Resample when N_eff < this fraction of the particle count, (0, 1].
  int min_particles = 4;            ///< Particles never drop below this when a level halves them, 1..100000.
  /// Distinct minima of the coarsest level carried to the level below, which decides among them,
  /// 2..1000. With one, nothing would check the coarse answer at a finer level, and a place that only
  /// looks right when pooled would be accepted (MrsSearch tests).
  int hypotheses = 8;
  std::uint64_t seed = 42;          ///< Seed of the search's random generator: same seed, same answer.

  void validate() const;
};

/// Every tunable of the core in one place.
struct Parameters {
  DescriptorParams descriptor;
  SequenceParams sequence;
  MrsParams mrs;

  void validate() const;
};

/// Parses "causal" / "centred" (also "centered"); throws std::invalid_argument otherwise.
WindowAlignment parseWindowAlignment(const std::string& text);
std::string toString(WindowAlignment alignment);

}  // namespace mrs_vpr
