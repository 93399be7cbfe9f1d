#include <exception>
#include <memory>

#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include "mrs_vpr/node/node_parameters.hpp"
#include "mrs_vpr/node/place_recognition_node.hpp"

namespace mrs_vpr {

/// The place recogniser as a nodelet (zero-copy images from a camera nodelet in the same manager).
class MrsVprNodelet : public nodelet::Nodelet {
 private:
  void onInit() override {
    ros::NodeHandle& private_nh = getPrivateNodeHandle();
    node::NodeParameters params;
    try {
      params = node::loadParameters(private_nh);
    } catch (const std::exception& error) {
      // A nodelet cannot exit its manager; it stays inert and says why.
      NODELET_FATAL("invalid parameters, not starting: %s", error.what());
      return;
    }
    for (const auto& name : node::unknownParameters(private_nh)) {
      NODELET_WARN("unknown parameter %s (ignored)", name.c_str());
    }
    // Images on the manager's single-threaded queue; the node serves queries on its own thread.
    node_ = std::make_unique<node::PlaceRecognitionNode>(getNodeHandle(), private_nh, params);
  }

  std::unique_ptr<node::PlaceRecognitionNode> node_;
};

}  // namespace mrs_vpr

PLUGINLIB_EXPORT_CLASS(mrs_vpr::MrsVprNodelet, nodelet::Nodelet)
