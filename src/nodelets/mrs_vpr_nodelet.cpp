#include <exception>
#include <memory>

#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include "mrs_vpr/node/place_recognition_node.hpp"

namespace mrs_vpr {

/// The place recogniser as a nodelet (zero-copy images from a camera nodelet in the same manager).
class MrsVprNodelet : public nodelet::Nodelet {
 private:
  void onInit() override {
    try {
      // Images on the manager's single-threaded queue; the node serves queries on its own thread.
      node_ = node::PlaceRecognitionNode::start(getNodeHandle(), getPrivateNodeHandle());
    } catch (const std::exception& error) {
      // A nodelet cannot exit its manager; it stays inert and says why (parameters, map database).
      NODELET_FATAL("not starting: %s", error.what());
    }
  }

  std::unique_ptr<node::PlaceRecognitionNode> node_;
};

}  // namespace mrs_vpr

PLUGINLIB_EXPORT_CLASS(mrs_vpr::MrsVprNodelet, nodelet::Nodelet)
