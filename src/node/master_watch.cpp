#include "mrs_vpr/node/master_watch.hpp"

#include <stdexcept>

#include <ros/connection_manager.h>
#include <ros/master.h>
#include <ros/network.h>
#include <ros/service_manager.h>
#include <ros/this_node.h>
#include <ros/xmlrpc_manager.h>
#include <xmlrpcpp/XmlRpc.h>

namespace mrs_vpr {
namespace node {
namespace {

using XmlRpc::XmlRpcValue;

XmlRpcValue callerOnly() {
  XmlRpcValue params;
  params[0] = ros::this_node::getName();
  return params;
}

/// The parameters of the master's register* calls: this node, the name registered, what it is
/// (a topic's type, a service's address) and this node's XML-RPC address.
XmlRpcValue registration(const std::string& name, const std::string& what, const std::string& caller_api) {
  XmlRpcValue params = callerOnly();
  params[1] = name;
  params[2] = what;
  params[3] = caller_api;
  return params;
}

/// A call of the ROS master API; the payload, or std::runtime_error with the master's reason.
XmlRpcValue callMaster(const std::string& method, const XmlRpcValue& params) {
  XmlRpcValue response;
  XmlRpcValue payload;
  // wait_for_master false: one attempt, no retries and no "waiting for master" messages.
  if (!ros::master::execute(method, params, response, payload, false)) {
    throw std::runtime_error(method + " failed at the master " + ros::master::getURI());
  }
  return payload;
}

/// A call of this process's own slave API (the list of its topics, a publisher update), as another
/// node would make it: roscpp offers no other way to list its subscriptions with their types.
XmlRpcValue callSelf(const std::string& method, const XmlRpcValue& params) {
  const std::string& uri = ros::XMLRPCManager::instance()->getServerURI();
  std::string host;
  uint32_t port = 0;
  if (!ros::network::splitURI(uri, host, port)) throw std::runtime_error("cannot parse this node's URI " + uri);
  XmlRpc::XmlRpcClient* client = ros::XMLRPCManager::instance()->getXMLRPCClient(host, port, "/");
  XmlRpcValue result;
  const bool answered = client->execute(method.c_str(), params, result);
  ros::XMLRPCManager::instance()->releaseXMLRPCClient(client);
  if (!answered || result.getType() != XmlRpcValue::TypeArray || result.size() != 3 ||
      result[0].getType() != XmlRpcValue::TypeInt || static_cast<int>(result[0]) != 1) {
    throw std::runtime_error(method + " failed at this node's own URI " + uri);
  }
  return result[2];
}

/// `read` over a reply of the master or of this node. XmlRpc reports a reply of unexpected types (a
/// /run_id set by hand to a number, a listing of another shape) with its own exception, which is no
/// std::exception and would end the node: it becomes std::runtime_error, as every other failure here.
template <typename Read>
auto readReply(const std::string& what, Read read) -> decltype(read()) {
  try {
    return read();
  } catch (const XmlRpc::XmlRpcException& error) {
    throw std::runtime_error(what + ": a reply of unexpected types (" + error.getMessage() + ")");
  }
}

/// [[topic, type], ...] of a slave API listing.
std::vector<std::pair<std::string, std::string>> topicsOf(XmlRpcValue listing) {
  return readReply("a topic listing", [&] {
    std::vector<std::pair<std::string, std::string>> topics;
    for (int i = 0; i < listing.size(); ++i) {
      topics.emplace_back(static_cast<std::string>(listing[i][0]), static_cast<std::string>(listing[i][1]));
    }
    return topics;
  });
}

}  // namespace

MasterEvent MasterState::observe(const std::string& identity) {
  if (identity.empty()) {
    if (lost_ || identity_.empty()) return MasterEvent::kNone;
    lost_ = true;
    return MasterEvent::kLost;
  }
  const bool was_lost = lost_;
  lost_ = false;
  if (identity_.empty()) {  // The first answer: the master this process registered with.
    identity_ = identity;
    return MasterEvent::kNone;
  }
  if (identity != identity_) {
    identity_ = identity;
    return MasterEvent::kRestarted;
  }
  return was_lost ? MasterEvent::kBack : MasterEvent::kNone;
}

MasterWatch::MasterWatch(double period) {
  // The master this process registered with, before any restart can happen unseen.
  state_.observe(masterIdentity());
  try {
    services_ = registeredServices();
  } catch (const std::exception&) {
    // Not answering already: the first check reports it.
  }
  nh_.setCallbackQueue(&queue_);
  // Wall time: a simulated /clock stops with the master that publishes it.
  timer_ = nh_.createWallTimer(ros::WallDuration(period), &MasterWatch::check, this);
  spinner_ = std::make_unique<ros::AsyncSpinner>(1, &queue_);
  spinner_->start();
}

MasterWatch::~MasterWatch() {
  timer_.stop();
  spinner_->stop();
}

std::string MasterWatch::masterIdentity() const {
  try {
    const int pid = readReply("getPid", [] { return static_cast<int>(callMaster("getPid", callerOnly())); });
    std::string run_id = "no run_id";
    XmlRpcValue params = callerOnly();
    params[1] = "/run_id";
    try {
      XmlRpcValue value = callMaster("getParam", params);
      // Set by hand to another type, it still tells this master from a new one.
      run_id = value.getType() == XmlRpcValue::TypeString ? static_cast<std::string>(value) : value.toXml();
    } catch (const std::exception&) {
      // A master started without roslaunch (rosmaster --core) has no /run_id; its pid still differs.
    }
    return run_id + " (pid " + std::to_string(pid) + ")";
  } catch (const std::exception&) {
    return "";
  }
}

std::vector<std::string> MasterWatch::registeredServices() const {
  XmlRpcValue state = callMaster("getSystemState", callerOnly());
  return readReply("getSystemState", [&] {
    std::vector<std::string> mine;
    XmlRpcValue& services = state[2];
    for (int i = 0; i < services.size(); ++i) {
      for (int j = 0; j < services[i][1].size(); ++j) {
        if (static_cast<std::string>(services[i][1][j]) == ros::this_node::getName()) {
          mine.push_back(static_cast<std::string>(services[i][0]));
        }
      }
    }
    return mine;
  });
}

std::string MasterWatch::reregister() const {
  const std::string caller_api = ros::XMLRPCManager::instance()->getServerURI();
  int publications = 0;
  for (const auto& topic : topicsOf(callSelf("getPublications", callerOnly()))) {
    callMaster("registerPublisher", registration(topic.first, topic.second, caller_api));
    ++publications;
  }
  int subscriptions = 0;
  for (const auto& topic : topicsOf(callSelf("getSubscriptions", callerOnly()))) {
    XmlRpcValue publishers = callMaster("registerSubscriber", registration(topic.first, topic.second, caller_api));
    // What roscpp does with the master's answer when it subscribes: connect to those publishers.
    XmlRpcValue update;
    update[0] = std::string("/master");
    update[1] = topic.first;
    update[2] = publishers;
    callSelf("publisherUpdate", update);
    ++subscriptions;
  }
  int services = 0;
  // The address roscpp gives the master when it advertises a service.
  const std::string service_api = "rosrpc://" + ros::network::getHost() + ":" +
                                  std::to_string(ros::ConnectionManager::instance()->getTCPPort());
  for (const std::string& service : services_) {
    if (!ros::ServiceManager::instance()->lookupServicePublication(service)) continue;  // since shut down
    callMaster("registerService", registration(service, service_api, caller_api));
    ++services;
  }
  return std::to_string(publications) + " publications, " + std::to_string(subscriptions) + " subscriptions and " +
         std::to_string(services) + " services";
}

void MasterWatch::check(const ros::WallTimerEvent&) {
  const std::string previous = state_.identity();
  const std::string identity = masterIdentity();
  switch (state_.observe(identity)) {
    case MasterEvent::kLost:
      ROS_WARN("mrs_vpr: the ROS master at %s does not answer; connections already made keep working, new ones "
               "wait for it",
               ros::master::getURI().c_str());
      return;
    case MasterEvent::kBack:
      ROS_INFO("mrs_vpr: the ROS master at %s answers again", ros::master::getURI().c_str());
      break;
    case MasterEvent::kRestarted:
      try {
        const std::string summary = reregister();
        ROS_WARN("mrs_vpr: the ROS master at %s was restarted (now %s, was %s) and knew nothing of this node: "
                 "registered %s with it again. Parameters set on the old master are gone; this node keeps the "
                 "values it read at start-up.",
                 ros::master::getURI().c_str(), identity.c_str(), previous.c_str(), summary.c_str());
      } catch (const std::exception& error) {
        ROS_ERROR("mrs_vpr: the ROS master at %s was restarted (now %s, was %s) and this node could not register "
                  "with it again (%s): restart this node",
                  ros::master::getURI().c_str(), identity.c_str(), previous.c_str(), error.what());
      }
      break;
    case MasterEvent::kNone:
      if (identity.empty()) return;
      break;
  }
  try {
    services_ = registeredServices();
  } catch (const std::exception&) {
    // The master went away between the two calls (or answered in another shape): the next check asks again.
  }
}

}  // namespace node
}  // namespace mrs_vpr
