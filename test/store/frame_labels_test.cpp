#include <gtest/gtest.h>

#include <string>

#include "mrs_vpr/store/frame_labels.hpp"

namespace mrs_vpr {
namespace {

TEST(FrameLabels, EachFrameKeepsItsFrameIdAndNumberInOrder) {
  FrameLabels labels;
  labels.append("camera", 0);
  labels.append("camera", 1);
  labels.append("", -1);
  labels.append("left", 7);
  labels.append("camera", 2);
  ASSERT_EQ(labels.size(), 5);
  EXPECT_EQ(labels.frameId(0), "camera");
  EXPECT_EQ(labels.frameId(2), "");
  EXPECT_EQ(labels.frameId(3), "left");
  EXPECT_EQ(labels.frameId(4), "camera");
  EXPECT_EQ(labels.sequence(3), 7);
  EXPECT_EQ(labels.sequence(2), -1);
  EXPECT_TRUE(labels.holds(4, "camera", 2));
  EXPECT_FALSE(labels.holds(4, "camera", 3));
  EXPECT_FALSE(labels.holds(4, "left", 2));
  EXPECT_FALSE(labels.holds(5, "camera", 2));
  EXPECT_FALSE(labels.holds(-1, "camera", 0));
  labels.clear();
  EXPECT_EQ(labels.size(), 0);
  EXPECT_FALSE(labels.holds(0, "camera", 0));
}

TEST(FrameLabels, ACamerasFramesHoldItsFrameIdOnce) {
  FrameLabels one_camera;
  FrameLabels every_frame_its_own;
  const std::string long_id(200, 'c');
  for (int i = 0; i < 10000; ++i) {
    one_camera.append(long_id, i);
    every_frame_its_own.append(long_id + std::to_string(i), i);
  }
  EXPECT_LT(one_camera.memoryBytes(), 2U * 10000U * 12U + 1000U);  // 12 a frame with room to grow, the id once
  EXPECT_GT(every_frame_its_own.memoryBytes(), 10000U * 200U);
  EXPECT_EQ(every_frame_its_own.frameId(9999), long_id + "9999");
  EXPECT_EQ(one_camera.frameId(9999), long_id);
}

TEST(FrameLabels, AFramePreparedForIsAppendedWithoutAllocating) {
  // What PersistentMap relies on: between prepareFor and append the frame joins the map, and an
  // append that threw (std::bad_alloc) then would leave the map's frames and their labels apart.
  FrameLabels labels;
  for (int i = 0; i < 100; ++i) {
    const std::string id = i % 3 == 0 ? "a" : "b" + std::to_string(i);
    labels.prepareFor(id);
    const std::size_t bytes = labels.memoryBytes();
    labels.append(id, i);
    EXPECT_EQ(labels.memoryBytes(), bytes) << i;  // vectors' capacities, the table's buckets and nodes
  }
}

TEST(FrameLabels, AFrameIdPreparedForAFrameThatWasNotAdmittedIsNotKept) {
  // A camera that names every frame anew, standing still: none of its frames joins the map.
  FrameLabels labels;
  labels.append("camera", 0);
  const std::size_t before = labels.memoryBytes();
  for (int i = 0; i < 1000; ++i) {
    labels.prepareFor("frame_" + std::to_string(i));
    labels.cancelPrepared();
  }
  EXPECT_LE(labels.memoryBytes(), before + 64 * sizeof(void*));  // at most the table's buckets grew
  labels.prepareFor("camera");  // known already: nothing to undo
  labels.cancelPrepared();
  labels.append("camera", 1);
  labels.prepareFor("left");
  labels.append("left", 2);
  labels.cancelPrepared();  // after its append: the id is the frame's, and stays
  EXPECT_EQ(labels.frameId(2), "left");
  labels.append("right", 3);
  EXPECT_EQ(labels.frameId(3), "right");
  EXPECT_EQ(labels.frameId(0), "camera");
}

}  // namespace
}  // namespace mrs_vpr
