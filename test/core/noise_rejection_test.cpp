// Queries of places that are not in the map have a best end too, the least bad of many wrong ones.
// The acceptance rule must turn them all down, for both methods at the default threshold, while
// still accepting stretches of the mapped route.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <ostream>
#include <random>
#include <string>

#include <opencv2/core.hpp>

#include "mrs_vpr/descriptor.hpp"
#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/match.hpp"
#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/sequence_matcher.hpp"
#include "mrs_vpr/synthetic_route.hpp"
#include "support/route_fixture.hpp"

namespace mrs_vpr {
namespace {

using testing_support::DescribedRoute;
using testing_support::describeRoute;
using testing_support::globalSearchParams;
using testing_support::routeDescriptor;
using testing_support::routeParameters;
using testing_support::standardRoute;
using testing_support::within;

const std::array<std::string, 2> kMethods{"seqslam", "mrs"};
constexpr int kSequences = 40;
constexpr std::uint64_t kNoiseSeed = 1234;

/// Acceptance over a batch of queries; the highest confidence tells how close a batch came.
struct Tally {
  int queries = 0;
  int found = 0;
  int accepted = 0;
  float highest_confidence = 0.0F;

  void add(const Match& match) {
    ++queries;
    found += match.reference_index >= 0 ? 1 : 0;
    accepted += match.accepted ? 1 : 0;
    highest_confidence = std::max(highest_confidence, match.confidence);
  }
};

std::ostream& operator<<(std::ostream& out, const Tally& tally) {
  return out << tally.accepted << " of " << tally.queries << " accepted (" << tally.found
             << " found), highest confidence " << tally.highest_confidence;
}

/// A uniform random-noise image. cv::randu draws from cv::theRNG(), which is seeded here from
/// `generator` (so the images are the same on every run) and restored afterwards (so other tests
/// see the generator they would see without this one).
cv::Mat noiseImage(std::mt19937_64& generator) {
  const cv::RNG saved = cv::theRNG();
  cv::theRNG() = cv::RNG(generator());
  cv::Mat image(64, 128, CV_8UC1);
  cv::randu(image, 0, 256);
  cv::theRNG() = saved;
  return image;
}

DescriptorSequence noiseSequence(int frames, std::mt19937_64& generator) {
  const DescriptorExtractor extractor{routeDescriptor()};
  DescriptorSequence sequence(extractor.size());
  for (int i = 0; i < frames; ++i) sequence.append(extractor.compute(noiseImage(generator)));
  return sequence;
}

/// Tally of `method` at the default parameters over kSequences noise sequences of `frames` frames.
Tally noiseQueries(const std::string& method, int frames) {
  const auto& route = standardRoute();
  const auto matcher = makeMatcher(method, routeParameters());
  std::mt19937_64 generator(kNoiseSeed);
  Tally tally;
  for (int i = 0; i < kSequences; ++i) {
    tally.add(matcher->match(route.reference.view(), noiseSequence(frames, generator).view()));
  }
  return tally;
}

/// The same kind of route as standardRoute() from another seed: other places, none of them mapped.
const DescribedRoute& unmappedRoute() {
  static const DescribedRoute route = [] {
    SyntheticRouteParams params;
    params.reference_frames = 600;
    params.query_frames = 400;
    params.seed = 8;
    return describeRoute(params);
  }();
  return route;
}

/// Tally of `method` over kSequences sequences of `frames` frames of `traversal`, spread evenly
/// over it.
Tally routeQueries(const std::string& method, const Parameters& params, const DescriptorSequence& traversal,
                   int frames, SequenceView map = standardRoute().reference.view()) {
  const auto matcher = makeMatcher(method, params);
  Tally tally;
  for (int i = 0; i < kSequences; ++i) {
    const int start = i * (traversal.size() - frames) / kSequences;
    tally.add(matcher->match(map, traversal.view(start, start + frames)));
  }
  return tally;
}

TEST(NoiseRejection, TenFrameNoiseSequencesAreNeverAccepted) {
  for (const std::string& method : kMethods) {
    const Tally tally = noiseQueries(method, 10);
    EXPECT_EQ(tally.accepted, 0) << method << ": " << tally;
  }
}

TEST(NoiseRejection, TwoFrameNoiseSequencesAreNeverAccepted) {
  for (const std::string& method : kMethods) {
    const Tally tally = noiseQueries(method, 2);
    EXPECT_EQ(tally.accepted, 0) << method << ": " << tally;
  }
}

TEST(NoiseRejection, ARouteFrameFollowedByABlackFrameIsNotAccepted) {
  // One real frame is no sequence: a black frame (every patch constant) carries no place at all.
  const auto& route = standardRoute();
  const DescriptorExtractor extractor{routeDescriptor()};
  const cv::Mat black = extractor.compute(cv::Mat::zeros(64, 128, CV_8UC3));
  for (const std::string& method : kMethods) {
    const auto matcher = makeMatcher(method, routeParameters());
    Tally tally;
    for (int i = 0; i < kSequences; ++i) {
      const int frame = 10 * i;
      DescriptorSequence query(extractor.size());
      query.append(route.query.descriptorRow(frame));
      query.append(black);
      tally.add(matcher->match(route.reference.view(), query.view()));
    }
    EXPECT_EQ(tally.accepted, 0) << method << ": " << tally;
  }
}

/// `reference` with its frames [begin, end) replaced by `black`.
DescriptorSequence mapBlackedOut(const DescriptorSequence& reference, const cv::Mat& black, int begin, int end) {
  DescriptorSequence map(reference.descriptorSize());
  for (int i = 0; i < reference.size(); ++i) {
    map.append(i >= begin && i < end ? black : reference.descriptorRow(i));
  }
  return map;
}

TEST(NoiseRejection, ACameraBlackedOutInTheMapAndAgainElsewhereGivesNoFalseLoopClosure) {
  // A covered lens, a dark tunnel or a saturated sky: every patch is constant, so all such frames
  // have the same descriptor wherever they were taken. The map holds 10 or 40 of them from reference
  // frame 200 on. The queries are taken elsewhere on the route, and their newest 0 to 30 of 30
  // frames are blacked out. Black against black costs nothing at every blacked-out frame alike, so it
  // must not make a place stand out. Measured (40 black in the map): accepted, all right, 23, 24, 12
  // and 1 of 42 with 0, 1, 10 and 20 frames black; none with 29 or 30 (highest confidence 0.63 and
  // 0.17).
  const auto& route = standardRoute();
  const DescriptorExtractor extractor{routeDescriptor()};
  const cv::Mat black = extractor.compute(cv::Mat::zeros(64, 128, CV_8UC3));
  constexpr int kBlackBegin = 200;
  constexpr int kFrames = 30;
  for (const int black_in_map : {10, 40}) {
    const int black_end = kBlackBegin + black_in_map;
    const DescriptorSequence map = mapBlackedOut(route.reference, black, kBlackBegin, black_end);
    for (const std::string& method : kMethods) {
      // The fine velocity step, so that the control (no frame black) is accepted as a rule.
      const auto matcher = makeMatcher(method, globalSearchParams());
      for (int blacked_out : {0, 1, 10, 20, 29, kFrames}) {
        Tally tally;
        int wrong_accepted = 0;
        for (int first = 0; first + kFrames <= route.query.size(); first += 5) {
          const int newest = first + kFrames - 1;
          const int truth = route.query_to_reference[static_cast<std::size_t>(newest)];
          if (truth >= kBlackBegin - kFrames && truth < black_end + kFrames) continue;  // elsewhere only
          DescriptorSequence query(extractor.size());
          for (int i = first; i <= newest; ++i) {
            query.append(i > newest - blacked_out ? black : route.query.descriptorRow(i));
          }
          const Match match = matcher->match(map.view(), query.view());
          tally.add(match);
          wrong_accepted += match.accepted && !within(match.reference_index, truth, 3) ? 1 : 0;
        }
        const std::string what = method + ", " + std::to_string(black_in_map) + " black in the map, " +
                                 std::to_string(blacked_out) + " of " + std::to_string(kFrames) +
                                 " in the query: ";
        EXPECT_EQ(wrong_accepted, 0) << what << tally;
        if (blacked_out == 0) EXPECT_GT(tally.accepted, tally.queries / 3) << what << tally;  // the control
        if (blacked_out == kFrames) EXPECT_EQ(tally.accepted, 0) << what << tally;
      }
    }
  }
}

TEST(NoiseRejection, SequencesOfAnUnmappedRouteAreNeverAccepted) {
  // Below 63 frames MRS has no coarser level and searches as brute force does; 100 and 200 frames
  // take it through its coarse-to-fine levels.
  for (const std::string& method : kMethods) {
    for (int frames : {50, 100, 200}) {
      const Tally tally = routeQueries(method, routeParameters(), unmappedRoute().query, frames);
      EXPECT_EQ(tally.accepted, 0) << method << ", " << frames << " frames: " << tally;
    }
  }
}

TEST(NoiseRejection, SequencesOfAnUnmappedRouteAreNeverAcceptedInASmallMap) {
  // A robot's map starts small. Among a few dozen wrong places the least bad one can stand out by
  // many spreads by chance, so a map needs kMinRivalEnds ends besides the answer's before anything
  // is accepted.
  for (const std::string& method : kMethods) {
    for (int map_frames : {20, 30, 50, 80, 110}) {
      const Tally tally = routeQueries(method, routeParameters(), unmappedRoute().query, 10,
                                       standardRoute().reference.view(0, map_frames));
      EXPECT_EQ(tally.accepted, 0) << method << ", map of " << map_frames << " frames: " << tally;
    }
  }
}

TEST(NoiseRejection, SequencesOfAnUnmappedRouteAreNotAcceptedAtTheControlsVelocityStep) {
  for (const std::string& method : kMethods) {
    const Tally tally = routeQueries(method, globalSearchParams(), unmappedRoute().query, 50);
    EXPECT_EQ(tally.accepted, 0) << method << ": " << tally;
  }
}

TEST(NoiseRejection, LongSequencesOfAnUnmappedRouteAreRarelyAcceptedWithAFineVelocityStep) {
  // A known limitation on this generated route, pinned so that it cannot grow unseen: both methods
  // accept 2 of 40 of the 100-frame sequences (frames 82..181 as reference 160 at confidence 3.88,
  // frames 97..196 as 176 at 3.59; the highest confidence of the rest is 2.97): in a map of 600 frames
  // mrs searches N = 100 at full resolution, as seqslam does, and their trajectories run inside the
  // velocity bounds. 200 frames: none accepted by either.
  for (const std::string& method : kMethods) {
    const Tally hundred = routeQueries(method, globalSearchParams(), unmappedRoute().query, 100);
    EXPECT_LE(hundred.accepted, 2) << method << ", 100 frames: " << hundred;
    const Tally two_hundred = routeQueries(method, globalSearchParams(), unmappedRoute().query, 200);
    EXPECT_EQ(two_hundred.accepted, 0) << method << ", 200 frames: " << two_hundred;
  }
}

TEST(NoiseRejection, SequencesOfTheMappedRouteAreAccepted) {
  // The control: the rule does not just reject everything. Like the other global-query tests it
  // needs the fine velocity step: at the default 0.1 a 50-frame trajectory drifts up to 2.5 frames
  // off this route's one-frame-wide dips, and of these 40 sequences 39 are still answered right but
  // only 20 accepted.
  const auto& route = standardRoute();
  for (const std::string& method : kMethods) {
    const auto matcher = makeMatcher(method, globalSearchParams());
    constexpr int kFrames = 50;
    for (int i = 0; i < kSequences; ++i) {
      const int start = i * (route.query.size() - kFrames) / kSequences;
      const int end = start + kFrames - 1;
      const Match match = matcher->match(route.reference.view(), route.query.view(start, end + 1));
      EXPECT_TRUE(within(match.reference_index, route.query_to_reference[static_cast<std::size_t>(end)], 3))
          << method << ", frames " << start << ".." << end << ": got " << match.reference_index;
      EXPECT_TRUE(match.accepted) << method << ", frames " << start << ".." << end << ": confidence "
                                  << match.confidence;
    }
  }
}

}  // namespace
}  // namespace mrs_vpr
