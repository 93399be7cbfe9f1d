#pragma once

// The real-data benchmark's queries: one method's answers to test sequences (global protocol) or to
// every frame (per-frame protocol), as records scored against the true places.

#include <cstdint>
#include <functional>
#include <vector>

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/evaluation/evaluation.hpp"
#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/sequence_matcher.hpp"
#include "real_references.hpp"
#include "truth_diagnosis.hpp"

namespace mrs_vpr {
namespace benchmark {

/// One method's answers to the test sequences of `length` frames of `query` that end at `ends`, in
/// `map`; the sequence ending at frame e has the true places truth_of(e). With `diagnosis`, MRS's
/// levels are traced into it.
std::vector<QueryRecord> globalRecords(const mrs_vpr::SequenceMatcher& matcher, mrs_vpr::SequenceView map,
                                       const DescriptorSequence& query, const std::vector<int>& ends, int length,
                                       const std::function<std::vector<int>(int)>& truth_of, TruthDiagnosis* diagnosis,
                                       int tolerance, double accept_threshold);

/// Runs one method on test sequences ending at the given frames of the route, in `reference`.
std::vector<QueryRecord> runGlobal(const mrs_vpr::SequenceMatcher& matcher, const Reference& reference,
                                   const DescriptorSequence& query, const std::vector<int>& ends, int length,
                                   bool out_of_map, TruthDiagnosis* diagnosis, int tolerance, double accept_threshold);

/// `params` for the per-frame rows: sequences of `length` frames at OpenSeqSLAM's velocity step 0.1,
/// enough for short sequences.
mrs_vpr::Parameters perFrameParams(const mrs_vpr::Parameters& params, int length);

/// The answers to every frame of `query` with a full sequence, in `map`; frame i's true places are
/// `truth_of(i)`.
std::vector<QueryRecord> perFrameRecords(const mrs_vpr::SequenceMatcher& matcher, mrs_vpr::SequenceView map,
                                         mrs_vpr::SequenceView query,
                                         const std::function<std::vector<int>(int)>& truth_of);

/// The per-frame answers to frames [first, last) of `query` in `reference`, each record indexed by its
/// frame of `query`; out of the map, no frame has a true place.
std::vector<QueryRecord> runPerFrame(const mrs_vpr::SequenceMatcher& matcher, const Reference& reference,
                                     const DescriptorSequence& query, int first, int last, bool out_of_map);

/// Seeded ends of test sequences of `length` frames that lie wholly inside frames [low, high], so that
/// out-of-map queries share no frame with the other part's reference.
std::vector<int> queryEnds(int low, int high, int length, int count, std::uint64_t seed);

}  // namespace benchmark
}  // namespace mrs_vpr
