// The node and a ROS master killed with SIGKILL and restarted on the same port. Not a rostest: the
// test owns the master, so that it can kill it.
#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <xmlrpcpp/XmlRpc.h>

#include "support/ros_processes.hpp"

namespace {

using mrs_vpr::testing_support::Child;
using mrs_vpr::testing_support::environmentFor;
using mrs_vpr::testing_support::freePort;
using mrs_vpr::testing_support::masterSays;
using mrs_vpr::testing_support::PrivateMaster;
using mrs_vpr::testing_support::rosmasterCommand;
using mrs_vpr::testing_support::waitFor;
using XmlRpc::XmlRpcValue;

/// True when the master lists `node` among the publishers (`kind` 0) or subscribers (1) of `topic`.
bool lists(int port, int kind, const std::string& node, const std::string& topic) {
  XmlRpc::XmlRpcClient client("localhost", port, "/");
  XmlRpcValue params;
  params[0] = std::string("/master_restart_test");
  XmlRpcValue result;
  if (!client.execute("getSystemState", params, result) || static_cast<int>(result[0]) != 1) return false;
  XmlRpcValue& entries = result[2][kind];
  for (int i = 0; i < entries.size(); ++i) {
    if (static_cast<std::string>(entries[i][0]) != topic) continue;
    for (int j = 0; j < entries[i][1].size(); ++j) {
      if (static_cast<std::string>(entries[i][1][j]) == node) return true;
    }
  }
  return false;
}

/// Sets a parameter on the master, as `rosparam set` does; true when the master accepts it.
bool setParameter(int port, const std::string& name, const XmlRpcValue& value) {
  XmlRpc::XmlRpcClient client("localhost", port, "/");
  XmlRpcValue params;
  params[0] = std::string("/master_restart_test");
  params[1] = name;
  params[2] = value;
  XmlRpcValue result;
  return client.execute("setParam", params, result) && static_cast<int>(result[0]) == 1;
}

bool publishes(int port, const std::string& node, const std::string& topic) { return lists(port, 0, node, topic); }
bool subscribes(int port, const std::string& node, const std::string& topic) { return lists(port, 1, node, topic); }

TEST(MasterRestart, TheNodeRegistersAgainWithAMasterRestartedAfterKill9) {
  const int port = freePort();
  ASSERT_GT(port, 0);
  const std::vector<std::string> environment = environmentFor(port);
  const std::vector<std::string> master_command = rosmasterCommand(port);
  const auto master_up = [port] { return masterSays(port, "getPid"); };
  const auto query_registered = [port] { return masterSays(port, "lookupService", "/mrs_vpr/query"); };

  auto master = std::make_unique<Child>(master_command, environment);
  ASSERT_TRUE(master->started());
  ASSERT_TRUE(waitFor(master_up, 30.0)) << "rosmaster did not start on port " << port;
  Child node({MRS_VPR_NODE_PATH, "__name:=mrs_vpr"}, environment);
  ASSERT_TRUE(node.started());
  ASSERT_TRUE(waitFor(query_registered, 30.0)) << "the node did not register ~query";
  // The image subscription is the node's last registration; the master is killed only after it.
  ASSERT_TRUE(waitFor([port] { return subscribes(port, "/mrs_vpr", "/image"); }, 30.0));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));

  master->stop(SIGKILL);
  ASSERT_FALSE(master_up());
  master = std::make_unique<Child>(master_command, environment);
  ASSERT_TRUE(waitFor(master_up, 30.0)) << "rosmaster did not restart on port " << port;

  // The node checks every second; the new master starts empty, so only the node can have told it.
  EXPECT_TRUE(waitFor(query_registered, 15.0)) << "the restarted master does not know ~query";
  EXPECT_TRUE(masterSays(port, "lookupService", "/mrs_vpr/reset"));
  EXPECT_TRUE(masterSays(port, "lookupNode", "/mrs_vpr"));
  EXPECT_TRUE(publishes(port, "/mrs_vpr", "/mrs_vpr/map_info"));
  EXPECT_TRUE(publishes(port, "/mrs_vpr", "/mrs_vpr/loop_closure"));
  EXPECT_TRUE(subscribes(port, "/mrs_vpr", "/image"));

  node.stop(SIGINT);
}

TEST(MasterRestart, ARunIdThatIsNoStringDoesNotStopTheNode) {
  // The master's /run_id tells a restarted master from the same one. Set by hand to a number, its
  // reading threw XmlRpc's own exception, which is no std::exception, and aborted the node.
  const PrivateMaster master;
  ASSERT_TRUE(master.started()) << "rosmaster did not start";
  const int port = master.port();
  ASSERT_TRUE(setParameter(port, "/run_id", XmlRpcValue(5)));
  Child node({MRS_VPR_NODE_PATH, "__name:=mrs_vpr"}, master.environment());
  ASSERT_TRUE(node.started());
  EXPECT_TRUE(waitFor([port] { return masterSays(port, "lookupService", "/mrs_vpr/query"); }, 30.0));
  // While it runs, too: the watch reads /run_id every second.
  ASSERT_TRUE(setParameter(port, "/run_id", XmlRpcValue(6)));
  std::this_thread::sleep_for(std::chrono::milliseconds(2500));
  EXPECT_TRUE(node.running());
  EXPECT_TRUE(masterSays(port, "lookupService", "/mrs_vpr/query"));
  node.stop(SIGINT);
}

}  // namespace
