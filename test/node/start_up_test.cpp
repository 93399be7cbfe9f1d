// A node that cannot start must end, with an error, rather than stay registered and do nothing: as a
// node, and as a nodelet standalone. Not a rostest: the test must see the process exit.
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "support/ros_processes.hpp"

namespace {

using mrs_vpr::testing_support::Child;
using mrs_vpr::testing_support::PrivateMaster;

/// The exit status of `command` run against `master`, or nothing when it still runs after 30 s.
std::optional<int> exitStatusOf(const PrivateMaster& master, const std::vector<std::string>& command) {
  Child child(command, master.environment());
  if (!child.started()) return std::nullopt;
  return child.exitWithin(30.0);
}

TEST(StartUp, ANodeWithABadParameterExitsWithAnError) {
  const PrivateMaster master;
  ASSERT_TRUE(master.started());
  const std::optional<int> status =
      exitStatusOf(master, {MRS_VPR_NODE_PATH, "__name:=bad_node", "_sequence/accept_threshold:=-1"});
  ASSERT_TRUE(status.has_value()) << "the node still runs";
  EXPECT_EQ(*status, 2);  // mrs_vpr_node's status for invalid parameters
}

TEST(StartUp, AStandaloneNodeletWithABadParameterExitsWithAnError) {
  // It stayed registered, with neither services nor topics, until it was killed.
  const PrivateMaster master;
  ASSERT_TRUE(master.started());
  const std::optional<int> status = exitStatusOf(master, {NODELET_PATH, "standalone", "mrs_vpr/MrsVprNodelet",
                                                          "__name:=bad_nodelet", "_sequence/accept_threshold:=-1"});
  ASSERT_TRUE(status.has_value()) << "the nodelet's process still runs";
  EXPECT_NE(*status, 0);
}

}  // namespace
