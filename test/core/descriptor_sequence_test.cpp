#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/mrs/patch_frequencies.hpp"
#include "support/front_ends.hpp"

namespace mrs_vpr {
namespace {

using testing_support::thumbnailParams;

constexpr int kSize = 16;

/// Descriptor of frame `f`: byte i = (7 f + 3 i) mod 251, distinct for every frame.
cv::Mat descriptorOf(int frame, int size = kSize) {
  cv::Mat row(1, size, CV_8U);
  for (int i = 0; i < size; ++i) row.at<std::uint8_t>(0, i) = static_cast<std::uint8_t>((7 * frame + 3 * i) % 251);
  return row;
}

DescriptorSequence sequenceOf(int frames, int size = kSize) {
  DescriptorSequence sequence(size);
  for (int f = 0; f < frames; ++f) sequence.append(descriptorOf(f, size), Stamp::fromNanoseconds(500'000'000LL * f));
  return sequence;
}

bool sameBytes(const std::uint8_t* data, const cv::Mat& row) {
  return std::equal(data, data + row.cols, row.ptr<std::uint8_t>(0));
}

template <typename Exception, typename Action>
std::string messageOf(Action action) {
  try {
    action();
  } catch (const Exception& error) {
    return error.what();
  }
  return "";
}

TEST(DescriptorSequence, AppendKeepsDescriptorsAndStampsInOrder) {
  DescriptorSequence sequence(kSize);
  EXPECT_TRUE(sequence.empty());
  EXPECT_EQ(sequence.descriptorSize(), kSize);
  for (int f = 0; f < 5; ++f) sequence.append(descriptorOf(f), Stamp::fromSecondsAndNanoseconds(10 + f, 7));
  ASSERT_EQ(sequence.size(), 5);
  EXPECT_FALSE(sequence.empty());
  for (int f = 0; f < 5; ++f) {
    EXPECT_TRUE(sameBytes(sequence.descriptor(f), descriptorOf(f))) << "frame " << f;
    EXPECT_EQ(sequence.stamp(f), Stamp::fromSecondsAndNanoseconds(10 + f, 7));
    // The row form reads the same stored bytes, without a copy.
    const cv::Mat row = sequence.descriptorRow(f);
    EXPECT_EQ(row.type(), CV_8UC1);
    EXPECT_EQ(row.rows, 1);
    EXPECT_EQ(row.cols, kSize);
    EXPECT_EQ(row.ptr<std::uint8_t>(0), sequence.descriptor(f));
  }
  EXPECT_GE(sequence.memoryBytes(), static_cast<std::size_t>(5 * kSize));
}

TEST(DescriptorSequence, AcceptsAnyContinuousEightBitMatrixOfTheRightSize) {
  DescriptorSequence sequence(kSize);
  const cv::Mat square = descriptorOf(3).reshape(1, 4);
  sequence.append(square);
  EXPECT_TRUE(sameBytes(sequence.descriptor(0), descriptorOf(3)));
}

TEST(DescriptorSequence, SizeOrTypeMismatchThrowsNamingTheExpectedDescriptor) {
  DescriptorSequence sequence(kSize);
  const std::string wrong_size = messageOf<std::invalid_argument>([&] { sequence.append(descriptorOf(0, 8)); });
  EXPECT_NE(wrong_size.find("must be 16 continuous bytes of CV_8UC1, got 8"), std::string::npos) << wrong_size;
  const std::string wrong_type =
      messageOf<std::invalid_argument>([&] { sequence.append(cv::Mat(1, kSize, CV_32F, cv::Scalar(0))); });
  EXPECT_NE(wrong_type.find("CV_8UC1"), std::string::npos) << wrong_type;
  EXPECT_NE(wrong_type.find("32F"), std::string::npos) << wrong_type;
  EXPECT_EQ(sequence.size(), 0);
  EXPECT_THROW(DescriptorSequence(0), std::invalid_argument);
}

TEST(DescriptorSequence, OutOfRangeAccessThrowsWithTheFrameAndSize) {
  const DescriptorSequence sequence = sequenceOf(10);
  const std::string message = messageOf<std::out_of_range>([&] { sequence.descriptor(10); });
  EXPECT_NE(message.find("frame 10"), std::string::npos) << message;
  EXPECT_NE(message.find("10 frames"), std::string::npos) << message;
  EXPECT_THROW(sequence.descriptor(-1), std::out_of_range);
  EXPECT_THROW(sequence.descriptorRow(10), std::out_of_range);
  EXPECT_THROW(sequence.stamp(10), std::out_of_range);
}

TEST(SequenceView, ViewSliceAndSubsampleAddressTheRightFrames) {
  const DescriptorSequence sequence = sequenceOf(20);
  const SequenceView whole = sequence.view();
  EXPECT_EQ(whole.count, 20);
  EXPECT_EQ(whole.descriptor_size, kSize);
  EXPECT_EQ(whole.step, 1);

  const SequenceView middle = sequence.view(5, 12);
  ASSERT_EQ(middle.count, 7);
  for (int i = 0; i < middle.count; ++i) EXPECT_TRUE(sameBytes(middle.frame(i), descriptorOf(5 + i)));

  const SequenceView every_third = whole.subsample(2, 3);  // Frames 2, 5, 8, 11, 14, 17.
  ASSERT_EQ(every_third.count, 6);
  EXPECT_EQ(every_third.step, 3);
  for (int i = 0; i < every_third.count; ++i) EXPECT_TRUE(sameBytes(every_third.frame(i), descriptorOf(2 + 3 * i)));

  // Slicing a subsampled view counts in its own frames: frames 5, 8, 11.
  const SequenceView nested = every_third.slice(1, 4);
  ASSERT_EQ(nested.count, 3);
  EXPECT_TRUE(sameBytes(nested.frame(2), descriptorOf(11)));

  EXPECT_EQ(whole.slice(7, 7).count, 0);
  EXPECT_EQ(whole.subsample(19, 5).count, 1);
}

TEST(SequenceView, InvalidSliceOrSubsampleThrowsOutOfRangeWithTheRange) {
  const SequenceView whole = sequenceOf(10).view();
  const std::string beyond = messageOf<std::out_of_range>([&] { whole.slice(3, 11); });
  EXPECT_NE(beyond.find("[3, 11)"), std::string::npos) << beyond;
  EXPECT_NE(beyond.find("10 frames"), std::string::npos) << beyond;
  EXPECT_THROW(whole.slice(-1, 2), std::out_of_range);
  EXPECT_THROW(whole.slice(5, 4), std::out_of_range);
  const std::string bad_stride = messageOf<std::out_of_range>([&] { whole.subsample(0, 0); });
  EXPECT_NE(bad_stride.find("stride 0"), std::string::npos) << bad_stride;
  EXPECT_THROW(whole.subsample(10, 1), std::out_of_range);
  EXPECT_THROW(whole.subsample(-1, 2), std::out_of_range);
}

/// kSize-byte descriptors as 4 x 4 images of 2 x 2 patches: 4 patches, 12-byte coarse cells.
DescriptorParams smallGeometry() {
  DescriptorParams geometry = thumbnailParams();
  geometry.image_width = 4;
  geometry.image_height = 4;
  geometry.patch_size = 2;
  return geometry;
}

TEST(DescriptorSequence, KeptCoarseCellsEqualCellsComputedOnDemand) {
  const PatchFrequencies frequencies(smallGeometry());
  DescriptorSequence sequence(kSize);
  sequence.keepCoarseCells(3, smallGeometry());  // Kept while frames are appended ...
  for (int f = 0; f < 37; ++f) sequence.append(descriptorOf(f));
  DescriptorSequence late = sequenceOf(37);
  late.keepCoarseCells(3, smallGeometry());  // ... and computed for frames already there.

  for (const DescriptorSequence* store : {&sequence, &late}) {
    for (int stride : {2, 4, 8}) {
      const SequenceView cells = store->view().coarseCells(stride, smallGeometry());
      ASSERT_EQ(cells.count, 36 / stride + 1) << "stride " << stride;
      ASSERT_EQ(cells.descriptor_size, 12);
      const DescriptorSequence expected = frequencies.cells(store->view(), 0, stride, cells.count);
      for (int j = 0; j < cells.count; ++j) {
        EXPECT_TRUE(std::equal(cells.frame(j), cells.frame(j) + 12, expected.descriptor(j)))
            << "stride " << stride << ", cell " << j;
      }
    }
    // Strides not kept, or another geometry: nothing.
    EXPECT_EQ(store->view().coarseCells(16, smallGeometry()).count, 0);
    DescriptorParams other = smallGeometry();
    other.patch_size = 4;
    EXPECT_EQ(store->view().coarseCells(2, other).count, 0);
  }
}

TEST(DescriptorSequence, CoarseCellsCostAFractionOfTheDescriptors) {
  // The default 64 x 32 descriptors with 8 x 8 patches: 96-byte cells at strides 1, 2, 4 and 8 are
  // 96 + 48 + 24 + 12 = 180 bytes a frame beside the 2048-byte descriptor and its 8-byte stamp.
  const DescriptorParams geometry = thumbnailParams();
  DescriptorSequence sequence(2048);
  sequence.keepCoarseCells(3, geometry);
  const int frames = 8000;
  sequence.reserve(frames);
  const cv::Mat frame(1, 2048, CV_8U, cv::Scalar(128));
  for (int f = 0; f < frames; ++f) sequence.append(frame);
  const double per_frame = static_cast<double>(sequence.memoryBytes()) / frames;
  EXPECT_LE(per_frame, 2048 + 8 + 180 + 1);
  EXPECT_GE(per_frame, 2048 + 8 + 180);
  EXPECT_LE(per_frame, 2.2 * 1024);
}

TEST(DescriptorSequence, PrefixSlicesKeepTheCoarseCellsOtherViewsDoNot) {
  DescriptorSequence sequence = sequenceOf(30);
  sequence.keepCoarseCells(2, smallGeometry());
  const SequenceView whole_cells = sequence.view().coarseCells(4, smallGeometry());
  const SequenceView prefix_cells = sequence.view(0, 21).coarseCells(4, smallGeometry());
  ASSERT_EQ(prefix_cells.count, 6);  // Cells 0 .. 20 / 4.
  EXPECT_EQ(prefix_cells.data, whole_cells.data);
  EXPECT_EQ(sequence.view(1, 21).coarseCells(4, smallGeometry()).count, 0);
  EXPECT_EQ(sequence.view().subsample(0, 2).coarseCells(4, smallGeometry()).count, 0);
}

TEST(DescriptorSequence, KeepCoarseCellsRejectsAGeometryOfAnotherSize) {
  DescriptorSequence sequence(kSize);
  const std::string message = messageOf<std::invalid_argument>([&] { sequence.keepCoarseCells(2, thumbnailParams()); });
  EXPECT_NE(message.find("thumbnail (64 x 32, patches of 8 px)"), std::string::npos) << message;
  EXPECT_NE(message.find("16 bytes"), std::string::npos) << message;
  DescriptorParams odd = smallGeometry();
  odd.patch_size = 3;
  EXPECT_THROW(sequence.keepCoarseCells(2, odd), std::invalid_argument);
}

TEST(DescriptorSequence, KeepCoarseCellsWithZeroLevelsStopsKeepingThem) {
  DescriptorSequence sequence = sequenceOf(12);
  sequence.keepCoarseCells(2, smallGeometry());
  EXPECT_NE(sequence.view().coarse, nullptr);
  sequence.keepCoarseCells(0, smallGeometry());
  EXPECT_EQ(sequence.view().coarse, nullptr);
  EXPECT_EQ(sequence.view().coarseCells(2, smallGeometry()).count, 0);
}

TEST(DescriptorSequence, ClearForgetsFramesAndCellsButKeepsTheirKind) {
  DescriptorSequence sequence = sequenceOf(12);
  sequence.keepCoarseCells(1, smallGeometry());
  sequence.clear();
  EXPECT_EQ(sequence.size(), 0);
  EXPECT_TRUE(sequence.empty());
  EXPECT_EQ(sequence.view().count, 0);
  EXPECT_EQ(sequence.view().coarseCells(2, smallGeometry()).count, 0);
  EXPECT_THROW(sequence.descriptor(0), std::out_of_range);

  // Frames appended after clear() get fresh, consistent cells.
  for (int f = 100; f < 105; ++f) sequence.append(descriptorOf(f));
  const SequenceView cells = sequence.view().coarseCells(2, smallGeometry());
  ASSERT_EQ(cells.count, 3);
  const DescriptorSequence expected = PatchFrequencies(smallGeometry()).cells(sequence.view(), 0, 2, 3);
  for (int j = 0; j < 3; ++j) {
    EXPECT_TRUE(std::equal(cells.frame(j), cells.frame(j) + 12, expected.descriptor(j))) << "cell " << j;
  }
}

}  // namespace
}  // namespace mrs_vpr
