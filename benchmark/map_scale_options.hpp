#pragma once

// The map-scale benchmark's command line.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mrs_vpr/parameters.hpp"

namespace mrs_vpr {
namespace benchmark {

/// What to measure; the parent process runs one child per map with `measure` and `truth_offset` set.
struct MapScaleOptions {
  std::string data;
  std::vector<long long> sizes = {10000, 100000, 1000000};
  std::string dir = "/tmp/mrs_vpr_map_scale";
  std::vector<int> lengths = {10, 50, 100, 300};
  int queries = 5;
  int brute_queries = 2;
  int threads = 1;
  int periods = 20;
  int keyframes_per_period = 3;
  std::uint64_t seed = 42;
  bool load_map = false;  ///< Also ~load_map's memory: a node's map replaced by the measured one.
  // Internal: measure one map in this process (the parent runs one child per size).
  std::string measure;
  DescriptorParams descriptor;  ///< The front end of the maps written.
  long long truth_offset = -1;
};

/// Parses and checks the command line; returns nothing after printing the help. Throws
/// std::invalid_argument (naming the option) for a bad value.
std::optional<MapScaleOptions> parseMapScaleOptions(int argc, char** argv);

/// A map size as the tables and file names write it: "10k", "1M", or the frames.
std::string sizeName(long long frames);

}  // namespace benchmark
}  // namespace mrs_vpr
