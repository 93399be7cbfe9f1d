#pragma once

#include <mutex>
#include <string>
#include <vector>

#include <ros/ros.h>

namespace mrs_vpr {
namespace testing_support {

/// Every message of a topic, collected by the spinner thread (the rostests' AsyncSpinner), for
/// tests that wait until the node has published something.
template <typename Message>
class TopicInbox {
 public:
  TopicInbox(ros::NodeHandle& nh, const std::string& topic)
      : sub_(nh.subscribe(topic, 100, &TopicInbox::callback, this)) {}

  /// Waits until the subscription is connected to a publisher: a message published before that is
  /// never delivered, and each test makes a new subscription.
  bool waitConnected(double timeout = 10.0) const {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
    while (sub_.getNumPublishers() == 0 && ros::ok() && ros::WallTime::now() < deadline) {
      ros::WallDuration(0.02).sleep();
    }
    return sub_.getNumPublishers() > 0;
  }

  /// The messages that arrived so far.
  std::vector<Message> messages() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return messages_;
  }

  /// Waits until `count` messages arrived; returns them (fewer on timeout).
  std::vector<Message> waitForCount(std::size_t count, double timeout = 10.0) {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && ros::WallTime::now() < deadline) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (messages_.size() >= count) return messages_;
      }
      ros::WallDuration(0.02).sleep();
    }
    std::lock_guard<std::mutex> lock(mutex_);
    return messages_;
  }

  /// Waits until a message satisfies `predicate`, the newest first; copies it to `found`.
  template <typename Predicate>
  bool waitFor(Predicate predicate, Message& found, double timeout = 20.0) {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && ros::WallTime::now() < deadline) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        for (auto it = messages_.rbegin(); it != messages_.rend(); ++it) {
          if (predicate(*it)) {
            found = *it;
            return true;
          }
        }
      }
      ros::WallDuration(0.02).sleep();
    }
    return false;
  }

  /// Every message received so far, oldest first.
  std::vector<Message> received() {
    std::lock_guard<std::mutex> lock(mutex_);
    return messages_;
  }

  void clear() {
    std::lock_guard<std::mutex> lock(mutex_);
    messages_.clear();
  }

  void shutdown() { sub_.shutdown(); }

 private:
  void callback(const Message& message) {
    std::lock_guard<std::mutex> lock(mutex_);
    messages_.push_back(message);
  }

  ros::Subscriber sub_;
  mutable std::mutex mutex_;
  std::vector<Message> messages_;
};

}  // namespace testing_support
}  // namespace mrs_vpr
