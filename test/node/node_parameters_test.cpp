#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "mrs_vpr/node/node_parameters.hpp"

namespace mrs_vpr {
namespace node {
namespace {

std::string errorOf(const NodeParameters& params) {
  try {
    params.validate();
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

std::map<std::string, ParameterDescription> descriptionsByName() {
  std::map<std::string, ParameterDescription> byName;
  for (const auto& description : describeParameters()) {
    byName[description.name] = description;
  }
  return byName;
}

TEST(NodeParameters, DefaultsAreValid) { EXPECT_NO_THROW(NodeParameters{}.validate()); }

TEST(NodeParameters, ErrorsNameTheParameterAndRange) {
  NodeParameters params;
  params.frame_stride = 0;
  EXPECT_EQ(errorOf(params), "~frame_stride must be in 1..10000, got 0");

  params = NodeParameters{};
  params.core.sequence.accept_threshold = -1.0;
  EXPECT_EQ(errorOf(params), "~sequence/accept_threshold must be in 0..1000, got -1");

  params = NodeParameters{};
  params.recognizer.default_method = "fast";
  EXPECT_EQ(errorOf(params), "~default_method must be one of mrs, seqslam, got 'fast'");

  params = NodeParameters{};
  params.recognizer.max_frames = 1;
  EXPECT_EQ(errorOf(params), "~max_frames must be 0 (unbounded) or >= 2, got 1");

  params = NodeParameters{};
  params.core.descriptor.image_width = 2;
  const std::string core = errorOf(params);
  EXPECT_NE(core.find("descriptor/image_width"), std::string::npos) << core;
  EXPECT_NE(core.find("4"), std::string::npos) << core;  // the range
}

// Periods and rates that ROS timers cannot hold, and distances of no finite size, are refused with the
// parameter's name instead of stopping the node in ros::Duration or keeping one keyframe for ever.
TEST(NodeParameters, PeriodsRatesAndDistancesMustBeFinite) {
  const double infinity = std::numeric_limits<double>::infinity();
  NodeParameters params;
  params.auto_query_period = 3e9;
  EXPECT_EQ(errorOf(params), "~auto_query_period must be in 0..86400, got 3000000000");
  params = NodeParameters{};
  params.map_info_rate = 1e-10;
  EXPECT_EQ(errorOf(params), "~map_info_rate must be in 0.001..1000, got 1e-10");
  params = NodeParameters{};
  params.threads = -1;
  EXPECT_EQ(errorOf(params), "~threads must be in 0..1024, got -1");
  params = NodeParameters{};
  params.min_frame_interval = infinity;
  EXPECT_EQ(errorOf(params), "~min_frame_interval must be in 0..86400, got inf");
  params = NodeParameters{};
  params.min_travel = infinity;
  EXPECT_EQ(errorOf(params), "~min_travel must be >= 0, got inf");
  params.min_travel = 1e6;
  EXPECT_EQ(errorOf(params), "");
}

TEST(NodeParameters, AutoQueryFramesDefaultsToSequenceLength) {
  NodeParameters params;
  params.core.sequence.sequence_length = 17;
  EXPECT_EQ(params.autoQueryFrames(), 17);
  params.auto_query_frames = 40;
  EXPECT_EQ(params.autoQueryFrames(), 40);
}

TEST(NodeParameters, DescriptionsCoverEveryParameterOnce) {
  const auto descriptions = describeParameters();
  std::set<std::string> names;
  for (const auto& description : descriptions) {
    EXPECT_TRUE(names.insert(description.name).second) << description.name;
    EXPECT_FALSE(description.default_value.empty()) << description.name;
    EXPECT_FALSE(description.range.empty()) << description.name;
    EXPECT_FALSE(description.meaning.empty()) << description.name;
  }
  EXPECT_EQ(names.count("mrs/tau"), 1U);
  EXPECT_EQ(names.count("descriptor/image_width"), 1U);
  EXPECT_EQ(names.count("min_frame_interval"), 1U);
  EXPECT_EQ(names.count("database"), 1U);
  EXPECT_EQ(names.count("min_travel"), 1U);
  EXPECT_EQ(names.count("descriptor/type"), 1U);
  EXPECT_EQ(names.count("descriptor/hog/cell_size"), 1U);
  EXPECT_EQ(names.count("min_appearance_change"), 1U);
  EXPECT_EQ(names.count("threads"), 1U);
  EXPECT_EQ(names.count("map_mode"), 1U);
  EXPECT_EQ(descriptions.size(), 48U);
}

/// Sets each int or double field of one table just outside its range, at each bounded end, and
/// expects validate() to name it as ~name with the range `--help` prints for it.
template <typename Group, typename Select>
void expectHelpRangeInEachMessage(const std::vector<ParameterSpec<Group>>& specs, Select select) {
  const auto help = descriptionsByName();
  for (const auto& spec : specs) {
    ASSERT_EQ(help.count(spec.info.name), 1U) << spec.info.name;
    const std::string& range = help.at(spec.info.name).range;
    EXPECT_EQ(range, spec.info.allowed());
    std::visit(
        [&](auto member) {
          using Value = std::decay_t<decltype(select(std::declval<NodeParameters&>()).*member)>;
          if constexpr (std::is_same_v<Value, int> || std::is_same_v<Value, double>) {
            const Range& r = spec.info.range;
            std::vector<double> outside;
            const double step = std::is_same_v<Value, int> ? 1.0 : 1e-9 * std::max(1.0, std::fabs(r.high));
            if (std::isfinite(r.low)) outside.push_back(r.low_open ? r.low : r.low - step);
            if (std::isfinite(r.high)) outside.push_back(r.high_open ? r.high : r.high + step);
            for (double value : outside) {
              NodeParameters params;
              select(params).*member = static_cast<Value>(value);
              const std::string message = errorOf(params);
              EXPECT_EQ(message.rfind("~" + spec.info.name + " must be", 0), 0U) << value << ": " << message;
              EXPECT_NE(message.find(range), std::string::npos) << message;
            }
          }
        },
        spec.member);
  }
}

TEST(NodeParameters, HelpRangeIsTheRangeEachMessageGives) {
  expectHelpRangeInEachMessage(descriptorParameters(),
                               [](NodeParameters& p) -> DescriptorParams& { return p.core.descriptor; });
  expectHelpRangeInEachMessage(sequenceParameters(),
                               [](NodeParameters& p) -> SequenceParams& { return p.core.sequence; });
  expectHelpRangeInEachMessage(mrsParameters(), [](NodeParameters& p) -> MrsParams& { return p.core.mrs; });
  expectHelpRangeInEachMessage(nodeParameters(), [](NodeParameters& p) -> NodeParameters& { return p; });
  expectHelpRangeInEachMessage(commitParameters(), [](NodeParameters& p) -> CommitPolicy& { return p.commit; });

  // The text parameter and a rule involving two parameters, with the words of --help too.
  const auto help = descriptionsByName();
  NodeParameters params;
  params.recognizer.default_method = "fast";
  EXPECT_NE(errorOf(params).find(help.at("default_method").range), std::string::npos) << errorOf(params);
  params = NodeParameters{};
  params.core.descriptor.patch_size = 6;
  EXPECT_NE(errorOf(params).find(help.at("descriptor/patch_size").range), std::string::npos) << errorOf(params);
}

TEST(NodeParameters, TheDatabaseIsAnyPathAndEmptyMeansMemoryOnly) {
  NodeParameters params;
  EXPECT_EQ(params.database, "");
  params.database = "maps/a map with spaces.db";
  EXPECT_EQ(errorOf(params), "");
  EXPECT_EQ(descriptionsByName().at("database").range, "a file path; empty = memory only");
  EXPECT_EQ(descriptionsByName().at("database").default_value, "\"\"");
  params.commit.period = 0.0;
  EXPECT_EQ(errorOf(params), "~commit_period must be in (0, 3600], got 0");
}

TEST(NodeParameters, TravelNeedsTwoDifferentFramesOnlyWhenOn) {
  NodeParameters params;
  params.odom_frame = "";
  EXPECT_EQ(errorOf(params), "");  // ~min_travel 0: the frames are not used.
  params.min_travel = 0.5;
  EXPECT_EQ(errorOf(params),
            "~odom_frame and ~base_frame must name two different tf frames, without a leading '/' (tf2 refuses it), "
            "when ~min_travel > 0 (got '' and 'base_link')");
  params.odom_frame = "base_link";
  EXPECT_NE(errorOf(params), "");
  // tf1's spelling: tf2 would refuse every lookup, and every image would be skipped as without a pose.
  params.odom_frame = "/map";
  EXPECT_NE(errorOf(params).find("got '/map' and 'base_link'"), std::string::npos) << errorOf(params);
  params.odom_frame = "map";
  EXPECT_EQ(errorOf(params), "");
  params.tf_timeout = 0.0;
  EXPECT_EQ(errorOf(params), "~tf_timeout must be in (0, 10], got 0");
}

TEST(NodeParameters, VelocityStepHelpSaysWhatIsChecked) {
  EXPECT_EQ(descriptionsByName().at("sequence/velocity_step").range, "(0, 10), at most 1000 velocities");
}

/// `name: value  # comment` entries of a YAML file of nested groups (by indentation), as
/// "group/subgroup/name" -> value; the comment, with its indented continuation lines, goes to `comments`.
std::map<std::string, std::string> readGroupedYaml(std::istream& in, std::map<std::string, std::string>& comments) {
  const auto trim = [](const std::string& text) {
    const auto first = text.find_first_not_of(" \t");
    const auto last = text.find_last_not_of(" \t");
    return first == std::string::npos ? std::string() : text.substr(first, last - first + 1);
  };
  std::map<std::string, std::string> values;
  std::vector<std::pair<std::size_t, std::string>> groups;  // (indentation, name) of the open groups
  std::string last_key;
  std::string line;
  while (std::getline(in, line)) {
    const auto hash = line.find('#');
    const std::string comment = hash == std::string::npos ? "" : trim(line.substr(hash + 1));
    const std::string content = line.substr(0, hash);
    const bool indented = !line.empty() && line[0] == ' ';
    if (trim(content).empty()) {
      if (indented && !last_key.empty()) {
        comments[last_key] += " " + comment;  // a continuation of the comment above
      } else {
        last_key.clear();
      }
      continue;
    }
    const auto colon = content.find(':');
    EXPECT_NE(colon, std::string::npos) << line;
    const std::string key = trim(content.substr(0, colon));
    const std::string value = trim(content.substr(colon + 1));
    const std::size_t indentation = content.find_first_not_of(' ');
    while (!groups.empty() && groups.back().first >= indentation) groups.pop_back();
    std::string path;
    for (const auto& open : groups) path += open.second + "/";
    if (value.empty()) {
      groups.emplace_back(indentation, key);  // a group's heading
      last_key.clear();
      continue;
    }
    last_key = path + key;
    EXPECT_EQ(values.count(last_key), 0U) << "listed twice: " << last_key;
    values[last_key] = value;
    comments[last_key] = comment;
  }
  return values;
}

TEST(NodeParameters, ParameterReferenceListsEveryParameterWithItsDefaultAndRange) {
  // Rows "| `name` | default | range | meaning |" of the parameter reference's table.
  std::ifstream file(std::string(MRS_VPR_SOURCE_DIR) + "/doc/parameters.md");
  ASSERT_TRUE(file.good());
  std::map<std::string, std::pair<std::string, std::string>> rows;
  for (std::string line; std::getline(file, line);) {
    if (line.rfind("| `", 0) != 0) continue;
    std::vector<std::string> cells;
    std::stringstream row(line.substr(1));
    for (std::string cell; std::getline(row, cell, '|');) cells.push_back(cell.substr(1, cell.size() - 2));
    if (cells.size() != 4) continue;
    const std::string name = cells[0].substr(1, cells[0].size() - 2);  // Without the backticks.
    rows[name] = {cells[1], cells[2]};
  }
  for (const auto& [name, description] : descriptionsByName()) {
    ASSERT_EQ(rows.count(name), 1U) << "doc/parameters.md's table does not list " << name;
    EXPECT_EQ(rows.at(name).first, description.default_value) << name;
    EXPECT_EQ(rows.at(name).second, description.range) << name;
  }
}

TEST(NodeParameters, DefaultYamlListsEveryParameterWithItsDefaultAndRange) {
  std::ifstream file(std::string(MRS_VPR_SOURCE_DIR) + "/config/default.yaml");
  ASSERT_TRUE(file.good());
  std::map<std::string, std::string> comments;
  const auto yaml = readGroupedYaml(file, comments);
  const auto help = descriptionsByName();
  for (const auto& [name, description] : help) {
    ASSERT_EQ(yaml.count(name), 1U) << "config/default.yaml does not list " << name;
    EXPECT_EQ(yaml.at(name), description.default_value) << name;
    // The comment gives the range in the words of --help, so it cannot drift from the check.
    EXPECT_NE(comments.at(name).find(description.range), std::string::npos)
        << name << ": comment '" << comments.at(name) << "' does not give the range " << description.range;
  }
  for (const auto& [name, value] : yaml) {
    EXPECT_EQ(help.count(name), 1U) << "config/default.yaml lists " << name << ", which the node does not know";
  }
}

TEST(UnknownParameters, ReportsTyposAlsoInGroups) {
  const std::vector<std::string> names = {"mrs/tau", "frame_stride", "sequnce/sequence_length",
                                          "sequence/lenght", "framestride", "descriptor/image_width"};
  const std::vector<std::string> expected = {"~sequnce/sequence_length", "~sequence/lenght", "~framestride"};
  EXPECT_EQ(unknownParameters(names), expected);
}

TEST(UnknownParameters, IgnoresImageTransportAndItsPlugins) {
  const std::vector<std::string> names = {"image_transport", "compressed/mode", "compressedDepth/depth_max",
                                          "theora/quality", "theora/optimize_for"};
  EXPECT_TRUE(unknownParameters(names).empty());
  // Only the plugins' namespaces: a name merely containing one is not let through.
  EXPECT_EQ(unknownParameters({"compressed", "my_compressed/mode", "image_transport/raw"}),
            (std::vector<std::string>{"~compressed", "~my_compressed/mode", "~image_transport/raw"}));
}

TEST(UnknownParameters, KnowsEveryDescribedParameter) {
  std::vector<std::string> names;
  for (const auto& description : describeParameters()) {
    names.push_back(description.name);
  }
  EXPECT_TRUE(unknownParameters(names).empty());
}

}  // namespace
}  // namespace node
}  // namespace mrs_vpr
