#include <exception>
#include <memory>
#include <stdexcept>

#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include "mrs_vpr/node/place_recognition_node.hpp"

namespace mrs_vpr {

/// The place recogniser as a nodelet (zero-copy images from a camera nodelet in the same manager).
class MrsVprNodelet : public nodelet::Nodelet {
 private:
  void onInit() override {
    // Images on the manager's single-threaded queue; the node serves queries on its own thread.
    // A nodelet that cannot start says why, as the node does, and throws: the loader then unloads it,
    // and a standalone nodelet's process exits with an error instead of staying registered, inert.
    try {
      node_ = node::PlaceRecognitionNode::start(getNodeHandle(), getPrivateNodeHandle());
    } catch (const std::invalid_argument& error) {
      NODELET_FATAL("mrs_vpr: invalid parameters, not starting: %s", error.what());
      throw;
    } catch (const std::exception& error) {  // the map database
      NODELET_FATAL("mrs_vpr: not starting: %s", error.what());
      throw;
    }
  }

  std::unique_ptr<node::PlaceRecognitionNode> node_;
};

}  // namespace mrs_vpr

PLUGINLIB_EXPORT_CLASS(mrs_vpr::MrsVprNodelet, nodelet::Nodelet)
