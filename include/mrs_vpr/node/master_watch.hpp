#pragma once

#include <memory>
#include <string>
#include <vector>

#include <ros/callback_queue.h>
#include <ros/ros.h>

namespace mrs_vpr {
namespace node {

/// What one look at the ROS master found, given what the looks before it found.
enum class MasterEvent {
  kNone,       ///< as before (up, or still down)
  kLost,       ///< it stopped answering
  kBack,       ///< the same master (same run_id and pid) answers again
  kRestarted,  ///< another master answers at the same address: it knows nothing of this node
};

/**
 * Tells a restarted ROS master from a master that was only unreachable, by its identity (the /run_id
 * roslaunch gives every roscore, and the master's process id). Pure bookkeeping, no ROS calls.
 */
class MasterState {
 public:
  /// `identity` is empty when the master did not answer.
  MasterEvent observe(const std::string& identity);

  /// The identity of the master last seen ("" before the first answer).
  const std::string& identity() const { return identity_; }

 private:
  std::string identity_;
  bool lost_ = false;
};

/**
 * Watches the ROS master and re-registers this process with a restarted one.
 *
 * roscpp registers publishers, subscribers and services with the master once, when they are created,
 * and cannot re-initialise (ros::init runs once per process). A master restarted after a crash
 * (`kill -9` of roscore) starts empty, so the node lived on unregistered: no one could find its
 * services or topics, and its subscribers never heard of new publishers. Every `period` seconds of
 * wall time this class asks the master for its identity; when a different master answers, it registers
 * again, under the same names and addresses, every publication and subscription of this process (as
 * its own XML-RPC slave API lists them, so those of image_transport and rosout too) and every service
 * it had registered with the old master, hands each subscription the publishers the new master knows,
 * and logs what it did. Connections already made between nodes do not go through the master and are
 * kept. Parameters set on the old master are not restored (the node keeps the values it read).
 *
 * The calls run on a thread and callback queue of their own, so that a master that does not answer
 * never delays an image or a query.
 */
class MasterWatch {
 public:
  static constexpr double kDefaultPeriod = 1.0;  // [s]

  explicit MasterWatch(double period = kDefaultPeriod);
  ~MasterWatch();

  MasterWatch(const MasterWatch&) = delete;
  MasterWatch& operator=(const MasterWatch&) = delete;

 private:
  void check(const ros::WallTimerEvent& event);

  /// The master's "run_id (pid N)", or "" when it does not answer.
  std::string masterIdentity() const;

  /// The services of this node that the master lists (kept from the last master that answered).
  std::vector<std::string> registeredServices() const;

  /// Registers everything again with the master now answering. Returns a summary, or throws
  /// std::runtime_error naming what failed.
  std::string reregister() const;

  MasterState state_;
  std::vector<std::string> services_;
  ros::CallbackQueue queue_;
  ros::NodeHandle nh_;
  ros::WallTimer timer_;
  std::unique_ptr<ros::AsyncSpinner> spinner_;
};

}  // namespace node
}  // namespace mrs_vpr
