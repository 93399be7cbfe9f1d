#pragma once

#include <string>

#include "mrs_vpr/node/bag_images.hpp"
#include "mrs_vpr/node/bag_poses.hpp"

namespace mrs_vpr {
namespace bag {

/// What the bag reader plugin hands to the bag library: countImages and forEachImage as
/// bag_images.hpp documents them, forEachTransform as bag_poses.hpp does, read with rosbag.
struct BagReaderTable {
  int (*count_images)(const std::string& bag_path, const std::string& topic);
  void (*for_each_image)(const std::string& bag_path, const std::string& topic, const ImageVisitor& visit, int start,
                         int count);
  void (*for_each_transform)(const std::string& bag_path, const TransformVisitor& visit);
};

/// The plugin's table, loaded on the first call. Throws std::runtime_error ("cannot load the bag
/// reader: ...") when the plugin cannot be loaded.
const BagReaderTable& bagReader();

/// The plugin's one exported symbol (unmangled, for dlsym).
constexpr const char* kBagReaderSymbol = "mrs_vpr_rosbag_reader_table";
/// The plugin's file name; it is installed beside the library that loads it.
constexpr const char* kBagReaderPluginFile = "libmrs_vpr_rosbag_reader.so";

}  // namespace bag
}  // namespace mrs_vpr
