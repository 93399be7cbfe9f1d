// mrs_vpr_node: live visual place recognition (see mrs_vpr/node/place_recognition_node.hpp).

#include <cstdio>
#include <cstring>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>

#include <ros/ros.h>

#include "mrs_vpr/memory_reuse.hpp"
#include "mrs_vpr/node/node_parameters.hpp"  // describeParameters, for --help
#include "mrs_vpr/node/place_recognition_node.hpp"

namespace {

void printHelp() {
  std::printf(
      "Usage: rosrun mrs_vpr mrs_vpr_node [image:=TOPIC] [_param:=value ...]\n"
      "       roslaunch mrs_vpr mrs_vpr.launch image:=TOPIC params:=FILE.yaml\n\n"
      "Subscribes:  image (sensor_msgs/Image; ~image_transport selects raw, compressed, ...)\n"
      "Publishes:   ~loop_closure (mrs_vpr/LoopClosure), ~map_info (mrs_vpr/MapInfo, latched),\n"
      "             ~loop_closure_stamps (std_msgs/Float64MultiArray, accepted closures only: [stamp of\n"
      "             the localised test frame, stamp of the reference frame] in seconds, as LIO-SAM's\n"
      "             lio_loop/loop_closure_detection takes them),\n"
      "             ~debug_image (sensor_msgs/Image, bgr8: the picture of each answer, drawn only while\n"
      "             someone subscribes)\n"
      "Services:    ~query (mrs_vpr/QuerySequence), ~reset (std_srvs/Trigger),\n"
      "             ~save_map (mrs_vpr/SaveMap), ~load_map (mrs_vpr/LoadMap)\n\n"
      "Parameters (private):\n");
  for (const auto& p : mrs_vpr::node::describeParameters()) {
    std::printf("  ~%-29s %-6s default %-8s range %s\n      %s\n", p.name.c_str(), p.type.c_str(),
                p.default_value.c_str(), p.range.c_str(), p.meaning.c_str());
  }
}

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0 ||
        std::strcmp(argv[i], "--params") == 0) {
      printHelp();
      return 0;
    }
  }
  mrs_vpr::retainFreedMemory();  // Queries reuse the memory earlier queries freed.
  ros::init(argc, argv, "mrs_vpr");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");

  std::unique_ptr<mrs_vpr::node::PlaceRecognitionNode> node;
  try {
    node = mrs_vpr::node::PlaceRecognitionNode::start(nh, private_nh);
  } catch (const std::invalid_argument& error) {
    ROS_FATAL("mrs_vpr: invalid parameters, not starting: %s", error.what());
    return 2;
  } catch (const std::exception& error) {
    ROS_FATAL("mrs_vpr: %s", error.what());
    return 1;
  }
  ros::spin();  // image callbacks; queries run on the node's own thread
  return 0;
}
