#include "map_scale_options.hpp"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include <boost/program_options.hpp>

#include "list_option.hpp"
#include "tools/descriptor_options.hpp"
#include "tools/tool_main.hpp"

namespace po = boost::program_options;

namespace mrs_vpr {
namespace benchmark {
namespace {

/// A map size as written on the command line: frames, or thousands ("10k") or millions ("1M").
long long parseSize(const std::string& text) {
  const std::invalid_argument bad("--sizes: bad size '" + text + "' (e.g. 10k, 1M; >= 2k)");
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::logic_error&) {  // No number at all, or out of range.
    throw bad;
  }
  const std::string unit = text.substr(used);
  const double scale = unit.empty() ? 1 : unit == "k" ? 1e3 : unit == "M" ? 1e6 : -1;
  if (scale < 0 || !(value * scale >= 2000) || value * scale > 1e12) throw bad;
  return static_cast<long long>(value * scale);
}

constexpr const char* kUsage =
    "Usage: mrs_vpr_map_scale_benchmark --data DIR [--sizes 10k,100k,1M] [--dir /tmp/mrs_vpr_map_scale]\n"
    "                                   [--lengths 10,50,100,300] [--queries 5] [--brute-queries 2]\n"
    "                                   [--threads 1] [--periods 20] [--keyframes-per-period 3] [--seed 42]\n"
    "                                   [--load-map]\n"
    "Writes map databases of real frames (DIR: the shared data folder) once, then loads each in a fresh\n"
    "process and prints load time, resident bytes a frame and both methods' query times.\n";

}  // namespace

std::string sizeName(long long frames) {
  if (frames % 1000000 == 0) return std::to_string(frames / 1000000) + "M";
  if (frames % 1000 == 0) return std::to_string(frames / 1000) + "k";
  return std::to_string(frames);
}

std::optional<MapScaleOptions> parseMapScaleOptions(int argc, char** argv) {
  MapScaleOptions options;
  std::vector<std::string> sizes;
  for (const long long frames : options.sizes) sizes.push_back(sizeName(frames));
  std::int64_t seed = static_cast<std::int64_t>(options.seed);  // Signed, so that a negative seed is refused.
  po::options_description description("Options");
  // clang-format off
  description.add_options()
      ("help,h", "print this help")
      ("data", po::value(&options.data)->required(), "the shared data folder (nordland/, corridor/)")
      ("sizes", listValue(&sizes), "map sizes in frames, comma-separated (e.g. 10k, 1M; >= 2k)")
      ("dir", po::value(&options.dir)->default_value(options.dir), "folder of the map databases, kept between runs")
      ("lengths", listValue(&options.lengths), "N: frames per test sequence, comma-separated")
      ("queries", po::value(&options.queries)->default_value(options.queries), "queries per map and kind (mrs)")
      ("brute-queries", po::value(&options.brute_queries)->default_value(options.brute_queries),
       "how many of them brute force answers too")
      ("threads", po::value(&options.threads)->default_value(options.threads), "threads of both methods")
      ("periods", po::value(&options.periods)->default_value(options.periods),
       "continuous mode: query periods timed (0 = no continuous-mode row)")
      ("keyframes-per-period", po::value(&options.keyframes_per_period)->default_value(options.keyframes_per_period),
       "continuous mode: keyframes joining the map between two queries")
      ("seed", po::value(&seed)->default_value(seed), "seed of the maps and of the queries")
      ("load-map", po::bool_switch(&options.load_map),
       "also ~load_map's memory: a node's map of the same frames replaced by the map")
      // The parent runs one child per map, with these two: the map to measure and where its true places are.
      ("measure", po::value(&options.measure), "internal: measure this map database in this process")
      ("truth-offset", po::value(&options.truth_offset)->default_value(options.truth_offset),
       "internal: index of the measured map's first true place");
  // clang-format on
  tools::addDescriptorOptions(description, options.descriptor);
  po::variables_map variables;
  if (!tools::parseCommandLine(argc, argv, kUsage, description, variables)) return std::nullopt;
  tools::refuseOtherFrontEndsOptions(variables, options.descriptor);
  options.sizes.clear();
  for (const std::string& size : sizes) options.sizes.push_back(parseSize(size));
  if (seed < 0) throw std::invalid_argument("--seed must be >= 0");
  options.seed = static_cast<std::uint64_t>(seed);
  const bool short_length = std::any_of(options.lengths.begin(), options.lengths.end(), [](int n) { return n < 10; });
  if (short_length || options.queries < 1 || options.brute_queries < 0 || options.threads < 1 || options.periods < 0 ||
      options.keyframes_per_period < 1) {
    throw std::invalid_argument(
        "--lengths each >= 10, --queries >= 1, --brute-queries >= 0, --threads >= 1, --periods >= 0, "
        "--keyframes-per-period >= 1");
  }
  // The options first, then the folder: checked before any map is written or any row printed.
  for (const char* folder : {"nordland/summer", "nordland/winter", "corridor"}) {
    if (!std::filesystem::is_directory(std::filesystem::path(options.data) / folder)) {
      throw std::invalid_argument("--data " + options.data + " has no folder " + folder +
                                  " (the shared data folder holds nordland/ and corridor/)");
    }
  }
  return options;
}

}  // namespace benchmark
}  // namespace mrs_vpr
