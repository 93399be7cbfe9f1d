#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/mrs/temporal_pooling.hpp"

namespace mrs_vpr {
namespace {

constexpr int kSize = 16;

/// Descriptor of frame `f`: byte i = (7 f + 3 i) mod 251, distinct for every frame.
cv::Mat descriptorOf(int frame, int size = kSize) {
  cv::Mat row(1, size, CV_8U);
  for (int i = 0; i < size; ++i) row.at<std::uint8_t>(0, i) = static_cast<std::uint8_t>((7 * frame + 3 * i) % 251);
  return row;
}

DescriptorSequence sequenceOf(int frames, int size = kSize) {
  DescriptorSequence sequence(size);
  for (int f = 0; f < frames; ++f) sequence.append(descriptorOf(f, size), 0.5 * f);
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
  for (int f = 0; f < 5; ++f) sequence.append(descriptorOf(f), 10.0 + f);
  ASSERT_EQ(sequence.size(), 5);
  EXPECT_FALSE(sequence.empty());
  for (int f = 0; f < 5; ++f) {
    EXPECT_TRUE(sameBytes(sequence.descriptor(f), descriptorOf(f))) << "frame " << f;
    EXPECT_DOUBLE_EQ(sequence.stamp(f), 10.0 + f);
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
  EXPECT_NE(wrong_size.find("16 bytes"), std::string::npos) << wrong_size;
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

TEST(DescriptorSequence, KeptPooledCellsEqualPoolSequence) {
  DescriptorSequence sequence(kSize);
  sequence.keepPooledCells(3, 4);  // Kept while frames are appended ...
  for (int f = 0; f < 37; ++f) sequence.append(descriptorOf(f));
  DescriptorSequence late = sequenceOf(37);
  late.keepPooledCells(3, 4);  // ... and computed for frames already there.

  for (const DescriptorSequence* store : {&sequence, &late}) {
    for (int stride : {2, 4, 8}) {
      const SequenceView cells = store->view().pooledCells(stride, 4);
      ASSERT_EQ(cells.count, 36 / stride + 1) << "stride " << stride;
      ASSERT_EQ(cells.descriptor_size, kSize / 4);
      const DescriptorSequence expected = poolSequence(store->view(), 0, stride, cells.count, 4);
      for (int j = 0; j < cells.count; ++j) {
        EXPECT_TRUE(std::equal(cells.frame(j), cells.frame(j) + kSize / 4, expected.descriptor(j)))
            << "stride " << stride << ", cell " << j;
      }
    }
    // Strides or pixel pooling not kept: nothing.
    EXPECT_EQ(store->view().pooledCells(16, 4).count, 0);
    EXPECT_EQ(store->view().pooledCells(2, 2).count, 0);
  }
}

TEST(DescriptorSequence, PooledCellIsTheMeanOfTheFramesEndingAtItsIndex) {
  DescriptorSequence sequence = sequenceOf(25);
  sequence.keepPooledCells(2, 2);
  const int stride = 4;
  const SequenceView cells = sequence.view().pooledCells(stride, 2);
  ASSERT_EQ(cells.count, 7);
  for (int j = 0; j < cells.count; ++j) {
    const int end = j * stride;
    const int begin = std::max(0, end - stride + 1);
    for (int o = 0; o < kSize / 2; ++o) {
      double sum = 0.0;
      for (int f = begin; f <= end; ++f) {
        sum += descriptorOf(f).at<std::uint8_t>(0, 2 * o) + descriptorOf(f).at<std::uint8_t>(0, 2 * o + 1);
      }
      const double mean = sum / (2.0 * (end - begin + 1));
      EXPECT_LE(std::abs(cells.frame(j)[o] - mean), 0.5 + 1e-6) << "cell " << j << ", byte " << o;
    }
  }
}

TEST(DescriptorSequence, PrefixSlicesKeepThePooledCellsOtherViewsDoNot) {
  DescriptorSequence sequence = sequenceOf(30);
  sequence.keepPooledCells(2, 1);
  const SequenceView whole_cells = sequence.view().pooledCells(4, 1);
  const SequenceView prefix_cells = sequence.view(0, 21).pooledCells(4, 1);
  ASSERT_EQ(prefix_cells.count, 6);  // Cells 0 .. 20 / 4.
  EXPECT_EQ(prefix_cells.data, whole_cells.data);
  EXPECT_EQ(sequence.view(1, 21).pooledCells(4, 1).count, 0);
  EXPECT_EQ(sequence.view().subsample(0, 2).pooledCells(4, 1).count, 0);
}

TEST(DescriptorSequence, KeepPooledCellsRejectsPoolingThatDoesNotDivideTheSize) {
  DescriptorSequence sequence(kSize);
  const std::string message = messageOf<std::invalid_argument>([&] { sequence.keepPooledCells(2, 3); });
  EXPECT_NE(message.find("pixel pooling 3"), std::string::npos) << message;
  EXPECT_NE(message.find("16"), std::string::npos) << message;
  EXPECT_THROW(sequence.keepPooledCells(2, 0), std::invalid_argument);
}

TEST(DescriptorSequence, KeepPooledCellsWithZeroLevelsStopsKeepingThem) {
  DescriptorSequence sequence = sequenceOf(12);
  sequence.keepPooledCells(2, 1);
  EXPECT_NE(sequence.view().pooled, nullptr);
  sequence.keepPooledCells(0, 1);
  EXPECT_EQ(sequence.view().pooled, nullptr);
  EXPECT_EQ(sequence.view().pooledCells(2, 1).count, 0);
}

TEST(DescriptorSequence, ClearForgetsFramesAndCellsButKeepsPooling) {
  DescriptorSequence sequence = sequenceOf(12);
  sequence.keepPooledCells(1, 2);
  sequence.clear();
  EXPECT_EQ(sequence.size(), 0);
  EXPECT_TRUE(sequence.empty());
  EXPECT_EQ(sequence.view().count, 0);
  EXPECT_EQ(sequence.view().pooledCells(2, 2).count, 0);
  EXPECT_THROW(sequence.descriptor(0), std::out_of_range);

  // Frames appended after clear() get fresh, consistent cells.
  for (int f = 100; f < 105; ++f) sequence.append(descriptorOf(f));
  const SequenceView cells = sequence.view().pooledCells(2, 2);
  ASSERT_EQ(cells.count, 3);
  const DescriptorSequence expected = poolSequence(sequence.view(), 0, 2, 3, 2);
  for (int j = 0; j < 3; ++j) {
    EXPECT_TRUE(std::equal(cells.frame(j), cells.frame(j) + kSize / 2, expected.descriptor(j))) << "cell " << j;
  }
}

}  // namespace
}  // namespace mrs_vpr
