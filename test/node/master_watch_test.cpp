#include <gtest/gtest.h>

#include "mrs_vpr/node/master_watch.hpp"

namespace mrs_vpr {
namespace node {
namespace {

TEST(MasterState, TheFirstAnswerIsTheMasterThisNodeRegisteredWith) {
  MasterState state;
  EXPECT_EQ(state.observe(""), MasterEvent::kNone);  // not up yet: nothing was lost
  EXPECT_EQ(state.observe("run-a (pid 10)"), MasterEvent::kNone);
  EXPECT_EQ(state.identity(), "run-a (pid 10)");
  EXPECT_EQ(state.observe("run-a (pid 10)"), MasterEvent::kNone);
}

TEST(MasterState, AMasterThatOnlyStoppedAnsweringComesBack) {
  MasterState state;
  state.observe("run-a (pid 10)");
  EXPECT_EQ(state.observe(""), MasterEvent::kLost);
  EXPECT_EQ(state.observe(""), MasterEvent::kNone);  // reported once
  EXPECT_EQ(state.observe("run-a (pid 10)"), MasterEvent::kBack);
  EXPECT_EQ(state.observe("run-a (pid 10)"), MasterEvent::kNone);
}

TEST(MasterState, AnotherMasterAtTheSameAddressIsARestart) {
  MasterState state;
  state.observe("run-a (pid 10)");
  EXPECT_EQ(state.observe(""), MasterEvent::kLost);
  EXPECT_EQ(state.observe("run-b (pid 11)"), MasterEvent::kRestarted);
  EXPECT_EQ(state.identity(), "run-b (pid 11)");
  EXPECT_EQ(state.observe("run-b (pid 11)"), MasterEvent::kNone);
  // Restarted between two looks, never seen down: still a restart.
  EXPECT_EQ(state.observe("run-c (pid 12)"), MasterEvent::kRestarted);
}

}  // namespace
}  // namespace node
}  // namespace mrs_vpr
