#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <stdexcept>
#include <string>

#include <unistd.h>

#include <opencv2/imgcodecs.hpp>

#include "mrs_vpr/evaluation/evaluation.hpp"
#include "mrs_vpr/evaluation/image_folder.hpp"

namespace mrs_vpr {
namespace {

namespace fs = std::filesystem;

QueryRecord record(int query, std::vector<int> truth, int predicted, float confidence, double time_ms = 1.0) {
  QueryRecord r;
  r.query_index = query;
  r.true_indices = std::move(truth);
  r.predicted_index = predicted;
  r.confidence = confidence;
  r.score = 1.0F - confidence;
  r.time_ms = time_ms;
  return r;
}

/// A fresh folder under the system's temporary directory, removed when the test ends.
class TempFolder {
 public:
  TempFolder() {
    const std::string name = std::string("mrs_vpr_eval_test_") +
                             ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" +
                             std::to_string(::getpid());
    path_ = fs::temp_directory_path() / name;
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempFolder() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  std::string path(const std::string& child = "") const {
    return child.empty() ? path_.string() : (path_ / child).string();
  }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name)) << text;
    return path(name);
  }

 private:
  fs::path path_;
};

std::string errorOf(const std::function<void()>& action) {
  try {
    action();
  } catch (const std::exception& error) {
    return error.what();
  }
  return "(no exception)";
}

// ------------------------------------------------------------------------------------------------
// Correctness and errors

TEST(Evaluation, CorrectWithinToleranceOfAnyTrueIndex) {
  EXPECT_TRUE(isCorrect(record(0, {10}, 12, 0.5F), 2));
  EXPECT_FALSE(isCorrect(record(0, {10}, 13, 0.5F), 2));
  EXPECT_TRUE(isCorrect(record(0, {3, 20}, 21, 0.5F), 1));   // Near the second true index.
  EXPECT_FALSE(isCorrect(record(0, {10}, -1, 0.5F), 100));   // No prediction.
  EXPECT_FALSE(isCorrect(record(0, {}, 5, 0.5F), 100));      // No true match exists.
  EXPECT_TRUE(isCorrect(record(0, {7}, 7, 0.5F), 0));
}

TEST(Evaluation, AbsoluteErrorIsToTheNearestTrueIndex) {
  EXPECT_EQ(absoluteError(record(0, {3, 20}, 17, 0.5F)), 3);
  EXPECT_EQ(nearestTrueIndex(record(0, {3, 20}, 17, 0.5F)), 20);
  EXPECT_EQ(nearestTrueIndex(record(0, {3, 20}, -1, 0.5F)), 3);
  EXPECT_EQ(absoluteError(record(0, {3}, -1, 0.5F)), -1);
  EXPECT_EQ(absoluteError(record(0, {}, 4, 0.5F)), -1);
}

// A keyframe stands for the frames up to the next keyframe: an answer naming it is right for any of
// them, and its error is counted from the nearest of them.
TEST(Evaluation, AKeyframeAnswerIsRightAnywhereInTheFramesItStandsFor) {
  Keyframes reference;
  reference.frames = {0, 10, 20};
  reference.total = 30;
  Match match;
  match.reference_index = 1;  // the keyframe at frame 10, standing for frames 10 to 19
  const QueryRecord inside = keyframeRecordOf(0, {15}, match, reference, 0.0);
  EXPECT_EQ(inside.predicted_index, 10);
  EXPECT_EQ(inside.predicted_last, 19);
  EXPECT_EQ(absoluteError(inside), 0);
  EXPECT_TRUE(isCorrect(inside, 0));
  const QueryRecord after = keyframeRecordOf(0, {22}, match, reference, 0.0);
  EXPECT_EQ(absoluteError(after), 3);  // from frame 19
  EXPECT_FALSE(isCorrect(after, 2));
  EXPECT_TRUE(isCorrect(after, 3));
  match.reference_index = 2;  // the last keyframe stands for the traversal's last frames
  EXPECT_EQ(keyframeRecordOf(0, {29}, match, reference, 0.0).predicted_last, 29);
}

TEST(Evaluation, TopOneAccuracy) {
  const std::vector<QueryRecord> records = {record(0, {0}, 0, 0.9F), record(1, {1}, 9, 0.8F),
                                            record(2, {2}, 3, 0.1F), record(3, {3}, -1, 0.0F)};
  EXPECT_DOUBLE_EQ(top1Accuracy(records, 0), 0.25);
  EXPECT_DOUBLE_EQ(top1Accuracy(records, 1), 0.5);
  EXPECT_TRUE(std::isnan(top1Accuracy({}, 1)));
  EXPECT_THROW(top1Accuracy(records, -1), std::invalid_argument);
}

TEST(Evaluation, TopOneAndRecallAreOverTheQueriesAboutPlacesInTheMap) {
  // Two queries about places outside the map (no true frame), one of them answered confidently: it
  // counts against precision, not against top-1 or recall, which a refusal would not change.
  std::vector<QueryRecord> records = {record(0, {0}, 0, 9.0F), record(1, {1}, 1, 8.0F), record(2, {2}, 30, 7.0F),
                                      record(3, {}, 40, 9.5F), record(4, {}, 50, 1.0F)};
  records[0].accepted = true;
  records[1].accepted = true;
  records[3].accepted = true;
  const EvaluationSummary summary = summarise(records, 1);
  EXPECT_EQ(summary.queries, 5);
  EXPECT_EQ(summary.queries_in_map, 3);
  EXPECT_DOUBLE_EQ(summary.top1, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(summary.accepted_recall, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(summary.accepted_precision, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(summary.accepted_rate, 0.6);
  // Curve: 9.5 wrong (P 0, R 0), 9 right (P .5, R 1/3), 8 right (P 2/3, R 2/3), 7 wrong, 1 wrong.
  EXPECT_NEAR(summary.pr_auc, 0.5 / 3.0 + (2.0 / 3.0) / 3.0, 1e-12);
  EXPECT_DOUBLE_EQ(precisionRecallCurve(records, 1).back().recall, 2.0 / 3.0);
  // Every confidence equal (the 0 of a map too small for the acceptance rule): no ranking, no area.
  for (QueryRecord& tied : records) tied.confidence = 0.0F;
  const EvaluationSummary unranked = summarise(records, 1);
  EXPECT_TRUE(std::isnan(unranked.pr_auc));
  EXPECT_TRUE(std::isnan(unranked.recall_at_100_precision));
  EXPECT_DOUBLE_EQ(unranked.top1, 2.0 / 3.0);
  // With none in the map, they mean nothing: NaN (null in the JSON), not 0.
  const EvaluationSummary outside = summarise({record(3, {}, 40, 9.5F), record(4, {}, 50, 1.0F)}, 1);
  EXPECT_EQ(outside.queries_in_map, 0);
  for (const double figure : {outside.top1, outside.pr_auc, outside.recall_at_100_precision, outside.accepted_recall}) {
    EXPECT_TRUE(std::isnan(figure));
  }
  EXPECT_TRUE(std::isnan(summarise({}, 1).accepted_recall));  // Nor with no query at all.
}

// ------------------------------------------------------------------------------------------------
// Precision-recall

TEST(Evaluation, PrecisionRecallCurveByHand) {
  // Confidence order: 0.9 correct, 0.8 wrong, 0.7 correct, 0.6 correct; a fifth query has no prediction.
  const std::vector<QueryRecord> records = {record(0, {0}, 0, 0.9F), record(1, {1}, 50, 0.8F),
                                            record(2, {2}, 2, 0.7F), record(3, {3}, 4, 0.6F),
                                            record(4, {4}, -1, 0.95F)};
  const std::vector<PrPoint> curve = precisionRecallCurve(records, 1);
  ASSERT_EQ(curve.size(), 4U);
  EXPECT_FLOAT_EQ(static_cast<float>(curve[0].threshold), 0.9F);
  EXPECT_DOUBLE_EQ(curve[0].precision, 1.0);
  EXPECT_DOUBLE_EQ(curve[0].recall, 0.2);
  EXPECT_DOUBLE_EQ(curve[1].precision, 0.5);
  EXPECT_DOUBLE_EQ(curve[1].recall, 0.2);
  EXPECT_DOUBLE_EQ(curve[2].precision, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(curve[2].recall, 0.4);
  EXPECT_DOUBLE_EQ(curve[3].precision, 0.75);
  EXPECT_DOUBLE_EQ(curve[3].recall, 0.6);
  // AP = 0.2 * 1 + 0 * 0.5 + 0.2 * 2/3 + 0.2 * 0.75.
  EXPECT_NEAR(averagePrecision(curve), 0.2 + 0.2 * 2.0 / 3.0 + 0.15, 1e-12);
  EXPECT_DOUBLE_EQ(recallAtFullPrecision(curve), 0.2);
}

TEST(Evaluation, AQueryRecordCopiesTheMatch) {
  Match match;
  match.reference_index = 12;
  match.confidence = 4.0F;
  match.score = 0.25F;
  match.accepted = true;
  const QueryRecord record = queryRecordOf(7, {12}, match, 2.5);
  EXPECT_EQ(record.query_index, 7);
  EXPECT_EQ(record.true_indices, std::vector<int>{12});
  EXPECT_EQ(record.predicted_index, 12);
  EXPECT_FLOAT_EQ(record.confidence, 4.0F);
  EXPECT_FLOAT_EQ(record.score, 0.25F);
  EXPECT_TRUE(record.accepted);
  EXPECT_FALSE(record.at_velocity_bound);
  EXPECT_DOUBLE_EQ(record.time_ms, 2.5);
  match.at_velocity_bound = true;
  EXPECT_TRUE(queryRecordOf(7, {12}, match, 2.5).at_velocity_bound);
}

TEST(Evaluation, EqualConfidencesAreAcceptedTogether) {
  const std::vector<QueryRecord> records = {record(0, {0}, 0, 0.5F), record(1, {1}, 30, 0.5F)};
  const std::vector<PrPoint> curve = precisionRecallCurve(records, 0);
  ASSERT_EQ(curve.size(), 1U);
  EXPECT_DOUBLE_EQ(curve[0].precision, 0.5);
  EXPECT_DOUBLE_EQ(curve[0].recall, 0.5);
  EXPECT_DOUBLE_EQ(averagePrecision(curve), 0.25);
  EXPECT_DOUBLE_EQ(recallAtFullPrecision(curve), 0.0);
}

TEST(Evaluation, AConfidenceThatIsNotANumberIsRefused) {
  // Before, the curve's loop never passed it and grew until memory ran out.
  const std::vector<QueryRecord> records = {record(0, {0}, 0, 0.5F), record(7, {1}, 1, std::nanf(""))};
  try {
    precisionRecallCurve(records, 0);
    ADD_FAILURE() << "a NaN confidence was taken";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(), "the record of query 7 has a confidence that is not a number");
  }
  EXPECT_THROW(summarise(records, 0), std::invalid_argument);
}

TEST(Evaluation, PerfectRankingHasUnitAreaAndFullRecall) {
  const std::vector<QueryRecord> records = {record(0, {0}, 0, 0.9F), record(1, {1}, 1, 0.3F),
                                            record(2, {2}, 2, 0.2F)};
  const std::vector<PrPoint> curve = precisionRecallCurve(records, 0);
  EXPECT_DOUBLE_EQ(averagePrecision(curve), 1.0);
  EXPECT_DOUBLE_EQ(recallAtFullPrecision(curve), 1.0);
}

TEST(Evaluation, ConfidentMistakeFirstLosesFullPrecision) {
  const std::vector<QueryRecord> records = {record(0, {0}, 40, 0.9F), record(1, {1}, 1, 0.8F)};
  const std::vector<PrPoint> curve = precisionRecallCurve(records, 0);
  EXPECT_DOUBLE_EQ(recallAtFullPrecision(curve), 0.0);
  EXPECT_DOUBLE_EQ(averagePrecision(curve), 0.25);  // Recall 0 -> 0.5 at precision 0.5.
  EXPECT_TRUE(precisionRecallCurve({}, 0).empty());
  EXPECT_DOUBLE_EQ(averagePrecision({}), 0.0);
}

// ------------------------------------------------------------------------------------------------
// Medians and the summary

TEST(Evaluation, Median) {
  EXPECT_DOUBLE_EQ(median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_DOUBLE_EQ(median({4.0, 1.0, 3.0, 2.0}), 2.5);
  EXPECT_DOUBLE_EQ(median({7.0}), 7.0);
  EXPECT_TRUE(std::isnan(median({})));
}

TEST(Evaluation, SummaryByHand) {
  const std::vector<QueryRecord> records = {record(0, {0}, 0, 0.9F, 2.0), record(1, {1}, 5, 0.8F, 4.0),
                                            record(2, {2, 3}, 4, 0.7F, 6.0), record(3, {3}, -1, 0.0F, 10.0)};
  const EvaluationSummary summary = summarise(records, 1);
  EXPECT_EQ(summary.tolerance, 1);
  EXPECT_EQ(summary.queries, 4);
  EXPECT_DOUBLE_EQ(summary.top1, 0.5);
  // Curve: (P 1, R .25), (P .5, R .25), (P 2/3, R .5).
  EXPECT_NEAR(summary.pr_auc, 0.25 + 0.25 * 2.0 / 3.0, 1e-12);
  EXPECT_DOUBLE_EQ(summary.recall_at_100_precision, 0.25);
  EXPECT_DOUBLE_EQ(summary.median_abs_error, 1.0);  // Errors 0, 4, 1.
  EXPECT_DOUBLE_EQ(summary.median_time_ms, 5.0);
  EXPECT_DOUBLE_EQ(summary.total_time_s, 0.022);
  EXPECT_EQ(summary.accepted, 0);
  EXPECT_TRUE(std::isnan(summary.accepted_precision));  // Nothing accepted: precision undefined.
  EXPECT_TRUE(std::isnan(summary.largest_wrong_accepted_error));  // ... and no wrong one.
  EXPECT_DOUBLE_EQ(summary.accepted_recall, 0.0);
}

TEST(Evaluation, AcceptedPrecisionRecallAndRate) {
  std::vector<QueryRecord> records = {record(0, {0}, 0, 9.0F), record(1, {1}, 5, 8.0F), record(2, {2}, 2, 7.0F),
                                      record(3, {}, 40, 1.0F)};  // The last place is not in the map.
  records[0].accepted = true;
  records[1].accepted = true;  // Wrong by 4 frames.
  records[3].accepted = false;
  const EvaluationSummary summary = summarise(records, 1);
  EXPECT_EQ(summary.accepted, 2);
  EXPECT_DOUBLE_EQ(summary.accepted_rate, 0.5);
  EXPECT_DOUBLE_EQ(summary.accepted_precision, 0.5);
  EXPECT_DOUBLE_EQ(summary.accepted_recall, 1.0 / 3.0);  // Of the 3 queries about places in the map.
  EXPECT_DOUBLE_EQ(summary.largest_wrong_accepted_error, 4.0);
  records[3].accepted = true;  // An answer about a place outside the map is always false ...
  EXPECT_DOUBLE_EQ(summarise(records, 1).accepted_precision, 1.0 / 3.0);
  // ... and has no distance to a true frame.
  EXPECT_DOUBLE_EQ(summarise(records, 1).largest_wrong_accepted_error, 4.0);
  records[1].accepted = false;
  EXPECT_TRUE(std::isnan(summarise(records, 1).largest_wrong_accepted_error));
}

// ------------------------------------------------------------------------------------------------
// Query selection of the two protocols

TEST(Evaluation, PerFrameQueriesHaveAFullSequence) {
  SequenceParams params;
  params.sequence_length = 3;
  params.alignment = WindowAlignment::kCausal;
  EXPECT_EQ(perFrameQueries(6, params), (std::vector<int>{2, 3, 4, 5}));
  params.alignment = WindowAlignment::kCentred;
  EXPECT_EQ(perFrameQueries(6, params), (std::vector<int>{1, 2, 3, 4}));
  params.sequence_length = 7;
  EXPECT_TRUE(perFrameQueries(6, params).empty());
}

TEST(Evaluation, GlobalQueriesAreSeededDistinctAndInside) {
  const std::vector<TestSequence> a = globalQueries(1000, 100, 200, 42);
  const std::vector<TestSequence> b = globalQueries(1000, 100, 200, 42);
  const std::vector<TestSequence> c = globalQueries(1000, 100, 200, 43);
  ASSERT_EQ(a.size(), 200U);
  std::set<int> starts;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].start, b[i].start);
    EXPECT_GE(a[i].start, 0);
    EXPECT_LE(a[i].start + a[i].length, 1000);
    EXPECT_EQ(a[i].length, 100);
    EXPECT_EQ(a[i].query_index, a[i].start + 99);
    if (i > 0) {
      EXPECT_LT(a[i - 1].start, a[i].start);
    }
    starts.insert(a[i].start);
  }
  EXPECT_EQ(starts.size(), 200U);
  bool differs = false;
  for (std::size_t i = 0; i < a.size(); ++i) differs = differs || a[i].start != c[i].start;
  EXPECT_TRUE(differs);
}

TEST(Evaluation, GlobalQueriesUseEveryPositionBeforeRepeating) {
  const std::vector<TestSequence> all = globalQueries(10, 8, 3, 1);  // Exactly 3 positions.
  ASSERT_EQ(all.size(), 3U);
  EXPECT_EQ(all[0].start, 0);
  EXPECT_EQ(all[1].start, 1);
  EXPECT_EQ(all[2].start, 2);
  const std::vector<TestSequence> more = globalQueries(10, 8, 5, 1);
  ASSERT_EQ(more.size(), 5U);
  std::set<int> distinct;
  for (const TestSequence& s : more) distinct.insert(s.start);
  EXPECT_EQ(distinct, (std::set<int>{0, 1, 2}));
  // The tools say so, as the summary counts a repeated test sequence again.
  EXPECT_EQ(repeatedGlobalQueries(10, 8, 3), "");
  EXPECT_EQ(repeatedGlobalQueries(10, 8, 5),
            "5 test sequences, but the query has 3 positions for one: each position once, and 2 of them again (the "
            "summary counts every test sequence)");
}

TEST(Evaluation, GlobalQueriesCentredLocaliseTheMiddle) {
  const std::vector<TestSequence> queries = globalQueries(50, 10, 5, 3, WindowAlignment::kCentred);
  ASSERT_EQ(queries.size(), 5U);
  for (const TestSequence& s : queries) {
    EXPECT_EQ(s.query_index, s.start + 5);
  }
}

TEST(Evaluation, GlobalQueriesRejectImpossibleRequests) {
  EXPECT_NE(errorOf([] { globalQueries(10, 11, 1, 0); }).find("do not fit"), std::string::npos);
  EXPECT_THROW(globalQueries(10, 0, 1, 0), std::invalid_argument);
  EXPECT_THROW(globalQueries(10, 2, -1, 0), std::invalid_argument);
  EXPECT_TRUE(globalQueries(10, 2, 0, 0).empty());
}

TEST(Evaluation, TruthFromGroundTruthOrIdentity) {
  const GroundTruth truth = {{0, {4, 5}}, {2, {}}};
  EXPECT_EQ(*truthFor(0, &truth, 10), (std::vector<int>{4, 5}));
  EXPECT_TRUE(truthFor(2, &truth, 10)->empty());
  EXPECT_FALSE(truthFor(1, &truth, 10).has_value());
  EXPECT_EQ(*truthFor(3, nullptr, 10), (std::vector<int>{3}));
  EXPECT_FALSE(truthFor(10, nullptr, 10).has_value());
}

// ------------------------------------------------------------------------------------------------
// Image folders

TEST(ImageFolder, ListsImagesInFileNameOrder) {
  TempFolder folder;
  for (const char* name : {"b.png", "a.png", "c.JPG", "notes.txt"}) {
    if (std::string(name) == "notes.txt") {
      folder.write(name, "not an image");
    } else {
      cv::imwrite(folder.path(name), cv::Mat(4, 6, CV_8UC3, cv::Scalar(1, 2, 3)));
    }
  }
  std::vector<std::string> left_out;
  const std::vector<std::string> files = listImageFiles(folder.path(), &left_out);
  ASSERT_EQ(files.size(), 3U);
  EXPECT_EQ(fs::path(files[0]).filename(), "a.png");
  EXPECT_EQ(fs::path(files[1]).filename(), "b.png");
  EXPECT_EQ(fs::path(files[2]).filename(), "c.JPG");
  EXPECT_EQ(left_out, std::vector<std::string>{"notes.txt"});
  EXPECT_EQ(leftOutNote(folder.path(), left_out),
            "left out 1 file of '" + folder.path() + "' not named as an image (notes.txt)");
  EXPECT_EQ(leftOutNote(folder.path(), {}), "");
}

// A camera that numbers its frames without zeros in front: frame 10 after frame 9, not after frame 1.
TEST(ImageFolder, NumbersInNamesSortAsNumbers) {
  TempFolder folder;
  for (const char* name : {"10.png", "9.png", "0.png", "1.png", "100.png", "2.png", "cam1_frame10.png",
                           "cam1_frame9.png", "cam2_frame1.png", "007.png"}) {
    folder.write(name, "");
  }
  std::vector<std::string> names;
  for (const std::string& file : listImageFiles(folder.path())) names.push_back(fs::path(file).filename().string());
  EXPECT_EQ(names, (std::vector<std::string>{"0.png", "1.png", "2.png", "007.png", "9.png", "10.png", "100.png",
                                             "cam1_frame9.png", "cam1_frame10.png", "cam2_frame1.png"}));
  // Zero-padded names, as most recordings write them, keep byte order.
  fs::create_directory(folder.path("padded"));
  for (const char* name : {"images-00190.png", "images-00180.png", "images-01000.png"}) {
    folder.write("padded/" + std::string(name), "");
  }
  std::vector<std::string> padded_names;
  for (const std::string& file : listImageFiles(folder.path("padded"))) {
    padded_names.push_back(fs::path(file).filename().string());
  }
  EXPECT_EQ(padded_names, (std::vector<std::string>{"images-00180.png", "images-00190.png", "images-01000.png"}));
  // Stamps written as seconds: the digits after the point are a fraction, not a number.
  fs::create_directory(folder.path("stamps"));
  for (const char* name : {"1614000000.3.png", "1614000000.05.png", "1614000000.25.png", "1614000000.1.png",
                           "1614000001.png", "999999999.9.png"}) {
    folder.write("stamps/" + std::string(name), "");
  }
  std::vector<std::string> stamp_names;
  for (const std::string& file : listImageFiles(folder.path("stamps"))) {
    stamp_names.push_back(fs::path(file).filename().string());
  }
  EXPECT_EQ(stamp_names, (std::vector<std::string>{"999999999.9.png", "1614000000.05.png", "1614000000.1.png",
                                                   "1614000000.25.png", "1614000000.3.png", "1614000001.png"}));
  // Read as counters the digits after the points would give another order: the tools say which they took.
  EXPECT_EQ(fractionOrderNote(listImageFiles(folder.path("stamps"))),
            "read '1614000000.05.png' before '1614000000.1.png', the digits after a point as a decimal fraction "
            "(stamps in seconds); if they count frames, write them with as many digits each (zeros in front)");
  EXPECT_EQ(fractionOrderNote(listImageFiles(folder.path("padded"))), "");
  EXPECT_EQ(fractionOrderNote(listImageFiles(folder.path())), "");
}

// A folder of images of an extension not known (.jfif, say) holds "no image": the message names its files.
TEST(ImageFolder, AFolderWithoutImagesNamesTheFilesItHolds) {
  TempFolder folder;
  for (int i = 0; i < 7; ++i) folder.write("frame" + std::to_string(i) + ".jfif", "an image of another name");
  const std::string message = errorOf([&] { listImageFiles(folder.path()); });
  EXPECT_EQ(message, "image folder '" + folder.path() + "' holds no image files (frame0.jfif, frame1.jfif, " +
                         "frame2.jfif, frame3.jfif, frame4.jfif and 2 more are not named as images: png, jpg, jpeg, " +
                         "bmp, tif, tiff, pgm, ppm, pnm, pbm, webp, jp2, gif)");
  // A folder of the traversals' folders (corridor/ for corridor/query), and a file alone.
  TempFolder parent;
  fs::create_directory(parent.path("query"));
  fs::create_directory(parent.path("ref"));
  parent.write("ground_truth.csv", "query_index,matching_ref_indices\n");
  EXPECT_EQ(errorOf([&] { listImageFiles(parent.path()); }),
            "image folder '" + parent.path() + "' holds no image files (ground_truth.csv is not named as an image: " +
                "png, jpg, jpeg, bmp, tif, tiff, pgm, ppm, pnm, pbm, webp, jp2, gif), and the folders query, ref");
  fs::remove(parent.path("ground_truth.csv"));
  EXPECT_EQ(errorOf([&] { listImageFiles(parent.path()); }),
            "image folder '" + parent.path() + "' holds no image files, only the folders query, ref");
}

// Skipped, a folder named as an image would shift every later frame's number.
TEST(ImageFolder, AFolderNamedAsAnImageIsAnError) {
  TempFolder folder;
  cv::imwrite(folder.path("0.png"), cv::Mat(4, 6, CV_8UC3, cv::Scalar(1, 2, 3)));
  fs::create_directory(folder.path("1.png"));
  EXPECT_EQ(errorOf([&] { listImageFiles(folder.path()); }), "image '" + folder.path("1.png") + "' is a folder");
  fs::remove(folder.path("1.png"));
  fs::create_directory(folder.path("subfolder"));  // Named as no image: skipped, as before.
  EXPECT_EQ(listImageFiles(folder.path()).size(), 1U);
}

// An image left out would shift the number of every later frame, and with it the ground truth.
TEST(ImageFolder, AnImageThatCannotBeListedIsAnErrorNotLeftOut) {
  TempFolder folder;
  cv::imwrite(folder.path("0.png"), cv::Mat(4, 6, CV_8UC3, cv::Scalar(1, 2, 3)));
  cv::imwrite(folder.path("1.webp"), cv::Mat(4, 6, CV_8UC3, cv::Scalar(1, 2, 3)));
  fs::create_symlink(folder.path("unmounted/2.png"), folder.path("2.png"));
  EXPECT_EQ(errorOf([&] { listImageFiles(folder.path()); }),
            "image '" + folder.path("2.png") + "' is a broken symbolic link (to '" + folder.path("unmounted/2.png") +
                "')");
  fs::remove(folder.path("2.png"));
  std::ofstream(folder.path("2.gif")) << "GIF89a";
  const std::vector<std::string> files = listImageFiles(folder.path());
  ASSERT_EQ(files.size(), 3U);
  EXPECT_EQ(loadImage(files[1]).size(), cv::Size(6, 4));  // WebP, read by OpenCV
  EXPECT_NE(errorOf([&] { loadImage(files[2]); }).find("2.gif': no image decoder of OpenCV reads it"),
            std::string::npos);
}

TEST(ImageFolder, LoadsImagesUnchanged) {
  TempFolder folder;
  cv::Mat gray16(5, 7, CV_16UC1, cv::Scalar(1000));
  cv::Mat bgr(5, 7, CV_8UC3, cv::Scalar(10, 20, 30));
  cv::imwrite(folder.path("0.png"), gray16);
  cv::imwrite(folder.path("1.png"), bgr);
  const std::vector<cv::Mat> images = loadImageFolder(folder.path());
  ASSERT_EQ(images.size(), 2U);
  EXPECT_EQ(images[0].type(), CV_16UC1);
  EXPECT_EQ(images[0].at<std::uint16_t>(2, 3), 1000);
  EXPECT_EQ(images[1].type(), CV_8UC3);
  EXPECT_EQ(images[1].at<cv::Vec3b>(0, 0), cv::Vec3b(10, 20, 30));
}

TEST(ImageFolder, ClearErrors) {
  TempFolder folder;
  const std::string missing = folder.path("missing");
  EXPECT_EQ(errorOf([&] { listImageFiles(missing); }), "image folder '" + missing + "' does not exist");

  const std::string empty = folder.path("empty");
  fs::create_directories(empty);
  EXPECT_EQ(errorOf([&] { listImageFiles(empty); }), "image folder '" + empty + "' holds no image files");

  const std::string file = folder.write("file.txt", "x");
  EXPECT_EQ(errorOf([&] { listImageFiles(file); }), "'" + file + "' is not a folder");

  const std::string broken = folder.path("broken");
  fs::create_directories(broken);
  cv::imwrite(broken + "/0.png", cv::Mat(4, 4, CV_8UC1, cv::Scalar(0)));
  std::ofstream(broken + "/1.png") << "not a png";
  EXPECT_EQ(errorOf([&] { loadImageFolder(broken); }),
            "cannot read image '" + broken + "/1.png': no image decoder of OpenCV reads it (a corrupt file, or a "
            "format this build of OpenCV lacks)");
  std::ofstream(broken + "/1.png", std::ios::trunc).close();
  EXPECT_EQ(errorOf([&] { loadImageFolder(broken); }), "cannot read image '" + broken + "/1.png': the file is empty");

  const std::string mixed = folder.path("mixed");
  fs::create_directories(mixed);
  cv::imwrite(mixed + "/0.png", cv::Mat(4, 4, CV_8UC1, cv::Scalar(0)));
  cv::imwrite(mixed + "/1.png", cv::Mat(4, 5, CV_8UC1, cv::Scalar(0)));
  const std::string message = errorOf([&] { loadImageFolder(mixed); });
  EXPECT_NE(message.find("1.png' is 5x4 but"), std::string::npos) << message;
  EXPECT_NE(message.find("0.png' is 4x4"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos);
}

TEST(ImageFolder, ATruncatedJpegFileIsRefusedNotReadHalfGrey) {
  TempFolder folder;
  cv::Mat texture(120, 160, CV_8UC3);
  cv::randu(texture, cv::Scalar::all(0), cv::Scalar::all(256));
  std::vector<std::uint8_t> jpeg;
  cv::imencode(".jpg", texture, jpeg);
  std::ofstream(folder.path("0.jpg"), std::ios::binary).write(reinterpret_cast<const char*>(jpeg.data()),
                                                                static_cast<std::streamsize>(jpeg.size()));
  std::ofstream(folder.path("1.JPEG"), std::ios::binary)
      .write(reinterpret_cast<const char*>(jpeg.data()), static_cast<std::streamsize>(jpeg.size() / 2));
  EXPECT_EQ(loadImage(folder.path("0.jpg")).size(), texture.size());
  EXPECT_EQ(errorOf([&] { loadImageFolder(folder.path()); }),
            "image '" + folder.path("1.JPEG") + "' is a truncated JPEG file (" + std::to_string(jpeg.size() / 2) +
                " bytes, no end-of-image marker)");
  // Cut as well, but ending with its end-of-image marker (bytes lost from the middle).
  std::vector<std::uint8_t> holed(jpeg.begin(), jpeg.begin() + static_cast<long>(jpeg.size() / 2));
  holed.insert(holed.end(), {0xFF, 0xD9});
  std::ofstream(folder.path("1.JPEG"), std::ios::binary)
      .write(reinterpret_cast<const char*>(holed.data()), static_cast<std::streamsize>(holed.size()));
  const std::string corrupt = errorOf([&] { loadImageFolder(folder.path()); });
  EXPECT_EQ(corrupt.find("image '" + folder.path("1.JPEG") + "' is a corrupt JPEG file, which libjpeg cannot " +
                         "decode without making up pixels: Corrupt JPEG data"),
            0U)
      << corrupt;
}

// ------------------------------------------------------------------------------------------------
// Ground-truth CSV

TEST(Evaluation, GroundTruthOutsideTheTraversalsIsRefusedNamingTheRow) {
  const GroundTruth fits = {{0, {0, 1}}, {4, {}}, {9, {49}}};
  EXPECT_NO_THROW(checkGroundTruth(fits, 10, 50));
  try {
    checkGroundTruth({{3, {1000, 1001}}}, 10, 50);
    FAIL() << "a reference frame beyond the reference passed";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("query frame 3"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("reference frame 1000"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("50 frames"), std::string::npos) << error.what();
  }
  EXPECT_THROW(checkGroundTruth({{0, {999999999}}}, 10, 50), std::invalid_argument);
  EXPECT_THROW(checkGroundTruth({{10, {1}}}, 10, 50), std::invalid_argument);  // Query frame 10 of 10.
}

TEST(GroundTruthCsv, ReadsSeveralMatchesPerQuery) {
  TempFolder folder;
  const std::string path =
      folder.write("gt.csv", "query_index,matching_ref_indices\r\n0,0 1 2\r\n1,0 1 2 3\n\n5,\n7, 9 \n");
  const GroundTruth truth = readGroundTruthCsv(path);
  ASSERT_EQ(truth.size(), 4U);
  EXPECT_EQ(truth.at(0), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(truth.at(1), (std::vector<int>{0, 1, 2, 3}));
  EXPECT_TRUE(truth.at(5).empty());
  EXPECT_EQ(truth.at(7), (std::vector<int>{9}));
}

TEST(GroundTruthCsv, ErrorsNameTheLine) {
  TempFolder folder;
  const std::string header = "query_index,matching_ref_indices\n";
  const std::string bad_header = folder.write("h.csv", "query,refs\n0,1\n");
  EXPECT_EQ(errorOf([&] { readGroundTruthCsv(bad_header); }),
            bad_header + ":1: expected the header 'query_index,matching_ref_indices', got 'query,refs'");
  const std::string no_comma = folder.write("c.csv", header + "0,1\n1 2\n");
  EXPECT_EQ(errorOf([&] { readGroundTruthCsv(no_comma); }),
            no_comma + ":3: expected 'query_index,ref ref ...', got '1 2'");
  const std::string negative = folder.write("n.csv", header + "0,1 -2\n");
  EXPECT_EQ(errorOf([&] { readGroundTruthCsv(negative); }),
            negative + ":2: reference index '-2' is not a non-negative integer");
  const std::string bad_query = folder.write("q.csv", header + "x,1\n");
  EXPECT_EQ(errorOf([&] { readGroundTruthCsv(bad_query); }),
            bad_query + ":2: query index 'x' is not a non-negative integer");
  const std::string twice = folder.write("t.csv", header + "0,1\n0,2\n");
  EXPECT_EQ(errorOf([&] { readGroundTruthCsv(twice); }), twice + ":3: query index 0 is listed twice");
  const std::string empty = folder.write("e.csv", "");
  EXPECT_NE(errorOf([&] { readGroundTruthCsv(empty); }).find("the file is empty"), std::string::npos);
  const std::string missing = folder.path("missing.csv");
  EXPECT_EQ(errorOf([&] { readGroundTruthCsv(missing); }), "cannot open ground-truth file '" + missing + "'");
}

}  // namespace
}  // namespace mrs_vpr
