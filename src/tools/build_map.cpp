// build_map: a map database from an image folder or a bag, for the node or mrs_vpr_eval to use.

#include <cstdint>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <boost/program_options.hpp>

#include "mrs_vpr/appearance_keyframes.hpp"
#include "mrs_vpr/descriptor.hpp"
#include "mrs_vpr/node/bag_images.hpp"
#include "mrs_vpr/node/bag_keyframes.hpp"
#include "mrs_vpr/node/ros_stamp.hpp"
#include "mrs_vpr/store/map_database.hpp"
#include "mrs_vpr/store/map_hold.hpp"
#include "mrs_vpr/store/map_traversal.hpp"
#include "apart_from_inputs.hpp"
#include "descriptor_options.hpp"
#include "drive_links.hpp"
#include "keyframing_options.hpp"
#include "output_in_progress.hpp"
#include "tool_main.hpp"
#include "traversal_closures.hpp"
#include "traversal_reader.hpp"

namespace po = boost::program_options;

namespace {

constexpr const char* kUsage =
    "Usage: build_map (--images DIR | --bag BAG --topic T [--min-travel M [--odom-frame F] [--base-frame B]])\n"
    "                 --output MAP.db [--min-appearance-change C] [--append] [--force] [--no-place-links]\n"
    "                 [--descriptor hog|thumbnail] [front-end options]\n"
    "       build_map --link-places --output MAP.db [--min-appearance-change C]\n"
    "\n"
    "Describes every image of DIR (file-name order) or of topic T in BAG and stores the descriptors,\n"
    "with their stamps (a bag's; frame i of DIR at i s) and their frame's index in DIR or on T (the frame\n"
    "numbers of mrs_vpr_eval's ground truth; with --append, numbered and stamped on after the map's\n"
    "frames), in the SQLite map database MAP.db. The map is written to MAP.db.part and renamed only when\n"
    "complete; an existing MAP.db is extended with --append (a copy of it, with the front end and the\n"
    "appearance change it records unless given) or replaced with --force. A failure leaves MAP.db as it\n"
    "was. The map records its traversal's frames and appearance change, by which mrs_vpr_eval judges it.\n"
    "With --min-travel, a frame of BAG is kept only once the robot is M metres from where the last kept\n"
    "one was taken, by the bag's own /tf (B in F at the frame's stamp), as the node's ~min_travel does.\n"
    "Otherwise a frame is kept once its view has changed by C of the difference between unrelated\n"
    "views, as the node's ~min_appearance_change keeps it (0: every frame).\n"
    "Loops are closed over the new frames as the node's continuous mode closes them at its defaults, and\n"
    "each accepted closure links its keyframe to the place it shows, so that a stretch the map now holds\n"
    "twice is no rival of itself (--no-place-links: none, faster, and the map is not held in memory).\n"
    "--link-places adds no frame: it closes the loops of a map built without them (--no-place-links, or by\n"
    "a release before place links), drive by drive, as if each drive had been added with them, and stores\n"
    "the links the map does not hold yet.\n";

/// Frames are committed in batches: one transaction per frame would be slow, one for all a long wait.
constexpr std::size_t kBatch = 1000;

/// What the command line asks for.
struct BuildOptions {
  std::string images;
  std::string bag_path;
  std::string topic;
  std::string output;
  bool append = false;
  bool force = false;
  bool no_place_links = false;
  bool link_places = false;  // No new frames: the map's own drives linked.
  mrs_vpr::bag::TravelSettings travel;
  mrs_vpr::DescriptorParams params;
  double min_appearance_change = mrs_vpr::RecognizerParams{}.min_appearance_change;
  bool descriptor_given = false;  // A front end named on the command line.
  bool min_appearance_change_given = false;  // Else an extended map's own, where it records one.
};

/// The command line's options, checked against each other; nullopt after --help.
std::optional<BuildOptions> parseOptions(int argc, char** argv) {
  BuildOptions options;
  po::options_description description("Options");
  // clang-format off
  description.add_options()
      ("help,h", "print this help")
      ("images", po::value(&options.images), "folder of images")
      ("bag", po::value(&options.bag_path), "bag of images")
      ("topic", po::value(&options.topic), "image topic in the bag")
      ("output", po::value(&options.output)->required(), "map database to write (*.db)")
      ("append", po::bool_switch(&options.append), "add to an existing map")
      ("force", po::bool_switch(&options.force), "replace an existing map")
      ("no-place-links", po::bool_switch(&options.no_place_links),
       "close no loops over the new frames, so link none of them to the places the map holds")
      ("link-places", po::bool_switch(&options.link_places),
       "add no frames: close the loops of the map's own drives, each against the frames before it, and "
       "store the links it does not hold yet");
  // clang-format on
  mrs_vpr::tools::addKeyframingOptions(
      description, options.travel, options.min_appearance_change,
      "with --bag: metres between kept frames, by the bag's /tf (0: keyframes by appearance change instead)",
      "keyframes by appearance change, as the node's ~min_appearance_change (when --min-travel is 0; with "
      "--append, the map's own where it records one); 0 = every frame");
  mrs_vpr::tools::addDescriptorOptions(description, options.params);
  po::variables_map variables;
  if (!mrs_vpr::tools::parseCommandLine(argc, argv, kUsage, description, variables)) return std::nullopt;
  mrs_vpr::tools::refuseOtherFrontEndsOptions(variables, options.params);
  mrs_vpr::tools::refuseEmptyPaths(variables, {"images", "bag", "output"});
  options.descriptor_given = mrs_vpr::tools::descriptorOptionsGiven(variables);
  options.min_appearance_change_given = mrs_vpr::tools::givenOnCommandLine(variables, "min-appearance-change");
  if (options.link_places) {
    if (!options.images.empty() || !options.bag_path.empty() || !options.topic.empty()) {
      throw std::invalid_argument("--link-places adds no frames: leave --images, --bag and --topic out");
    }
    if (options.append || options.force || options.no_place_links || options.travel.min_travel != 0.0) {
      throw std::invalid_argument("--link-places links the map as it is: leave --append, --force, --no-place-links "
                                  "and --min-travel out");
    }
    return options;
  }
  if (options.images.empty() == options.bag_path.empty()) throw std::invalid_argument("give either --images or --bag");
  if (!options.bag_path.empty() && options.topic.empty()) throw std::invalid_argument("reading a bag needs --topic");
  if (!options.images.empty() && !options.topic.empty()) {
    throw std::invalid_argument("--topic is for --bag: an image folder has no topic");
  }
  if (options.append && options.force) throw std::invalid_argument("--append and --force exclude each other");
  mrs_vpr::RecognizerParams keyframing;
  keyframing.min_appearance_change = options.min_appearance_change;
  keyframing.validate();
  if (options.travel.min_travel != 0.0 && options.bag_path.empty()) {
    throw std::invalid_argument("--min-travel needs --bag: the robot's poses come from the bag's /tf");
  }
  return options;
}

/// Adds the traversal's keyframes to `map`, chosen as the node keeps a camera's frames: by travel
/// (`keyframes`, when given), else by appearance change, which goes on from an appended map's last
/// keyframes. Leaves the map self-contained and reports on stderr what was kept; returns the frames added.
int addTraversal(mrs_vpr::MapDatabase& map, const BuildOptions& options,
                 std::optional<mrs_vpr::bag::BagKeyframes>& keyframes) {
  const mrs_vpr::DescriptorExtractor extractor(options.params);
  const std::int64_t before = map.size();
  const std::optional<mrs_vpr::MapTraversal> extended = map.traversal();  // Forgotten at the first append.
  mrs_vpr::AppearanceKeyframes appearance(options.params, keyframes ? 0.0 : options.min_appearance_change);
  // Each frame keeps its index in the traversal, so that a keyframed map can still be judged against
  // the traversal's frame numbers; an appended traversal is numbered on after the map's frames and
  // the traversal it records (those after its last keyframe too), as Python numbers them.
  mrs_vpr::FrameNumbering numbering;
  std::optional<mrs_vpr::tools::TraversalClosures> closures;
  if (!options.no_place_links) {
    closures.emplace(options.params, options.min_appearance_change, static_cast<int>(before));
  }
  map.forEachFrame([&](const mrs_vpr::StoredFrame& frame) {
    if (appearance.enabled()) appearance.keep(frame.descriptor);
    numbering.see(frame.sequence);
    if (closures) closures->addMapFrame(frame.descriptor, frame.stamp);
  });
  if (closures) closures->startTraversal(map.placeLinks(), map.driveStarts());
  // The traversal is another drive than the map's last: their junction is no place (drive_starts.hpp).
  if (before > 0) map.addDriveStart(static_cast<int>(before));
  std::int64_t next_index = numbering.next(extended);
  int stored = 0;
  int too_similar = 0;
  std::vector<mrs_vpr::StoredFrame> batch;
  const auto flush = [&] {
    map.append(batch, closures ? closures->takeLinks() : std::vector<mrs_vpr::PlaceLink>{});
    stored += static_cast<int>(batch.size());
    batch.clear();
  };
  const bool from_folder = !options.images.empty();
  mrs_vpr::tools::readTraversal(
      from_folder ? options.images : options.bag_path, options.topic, "map", extractor,
      [&](const cv::Mat& descriptor, mrs_vpr::Stamp stamp) {
        const std::int64_t index = next_index++;
        if (keyframes && !keyframes->keep(mrs_vpr::node::rosTimeOf(stamp))) return;
        if (!appearance.offer(descriptor)) {
          ++too_similar;
          return;
        }
        // A folder's frame i is stamped i s; an appended folder's frames go on from the map's numbers, so
        // that no two frames of one map share a stamp.
        const bool numbered_stamp = from_folder && index <= std::numeric_limits<std::uint32_t>::max();
        const mrs_vpr::Stamp kept_stamp =
            numbered_stamp ? mrs_vpr::Stamp::fromSecondsAndNanoseconds(static_cast<std::uint32_t>(index), 0) : stamp;
        batch.push_back({descriptor.clone(), kept_stamp, "", index});
        if (closures) closures->addKeyframe(descriptor, kept_stamp);
        if (batch.size() >= kBatch) flush();
      },
      from_folder ? mrs_vpr::tools::SourceKind::kFolder : mrs_vpr::tools::SourceKind::kBag);
  flush();
  // Frames after the last keyframe are still frames of the traversal, which a ground truth may name;
  // and a query keyframed as the map was lies on the map's scale. A map of keyframes kept in two ways
  // records none.
  mrs_vpr::MapTraversal traversal;
  traversal.frames = next_index;
  if (!keyframes) {
    const double kept_at = options.min_appearance_change;
    const bool as_the_map = extended && extended->min_appearance_change && *extended->min_appearance_change == kept_at;
    if (before == 0 || as_the_map) traversal.min_appearance_change = kept_at;
    const std::string mismatch = mrs_vpr::keyframingMismatch(extended, kept_at, "--min-appearance-change");
    if (before > 0 && !mismatch.empty()) std::cerr << "build_map: warning: " << mismatch << "\n";
  } else if (before > 0 && extended && extended->min_appearance_change) {
    std::cerr << "build_map: warning: the map's keyframes were kept at an appearance change of "
              << *extended->min_appearance_change << ", and these by travel (--min-travel): the map records no "
              << "keyframing now\n";
  }
  map.setTraversal(traversal);
  mrs_vpr::tools::stopIfInterrupted();  // Also one that came while the last frames were written.
  // A frame name tf does not know (or a bag without /tf for it) keeps no frame: no empty map.
  if (keyframes && stored == 0 && keyframes->withoutPose() > 0) {
    throw std::runtime_error("no frame was kept: " + keyframes->summary() +
                             "; the first frame without a pose: " + keyframes->firstMissingPose());
  }
  // The log copied in now, where a full disk is an error, not at the close, which cannot report it.
  map.makeSelfContained();
  std::cerr << "build_map: " << stored << " frames added to " << before << " in " << options.output << "\n";
  if (appearance.enabled()) {
    std::cerr << "build_map: " << too_similar << " frames too similar to a recent keyframe to be kept "
              << "(--min-appearance-change " << options.min_appearance_change << ")\n";
  }
  if (closures) {
    std::cerr << "build_map: " << closures->closures() << " loop closures accepted of " << closures->questions()
              << " questions about the new frames, which link them to the places they show (place links of "
              << "the map: " << map.placeLinks().size() << ")\n";
  }
  if (keyframes) {
    std::cerr << "build_map: " << keyframes->summary() << "\n";
    if (keyframes->withoutPose() > 0) {
      std::cerr << "build_map: warning: the first frame without a pose: " << keyframes->firstMissingPose() << "\n";
    }
  }
  return stored;
}

/// Links the map's own drives (--link-places) and reports on stderr what was linked.
void linkMapDrives(mrs_vpr::MapDatabase& map, const BuildOptions& options) {
  const mrs_vpr::tools::DriveLinking linked = mrs_vpr::tools::linkDrives(map, options.min_appearance_change);
  mrs_vpr::tools::stopIfInterrupted();
  map.makeSelfContained();
  std::cerr << "build_map: " << linked.closures << " loop closures accepted of " << linked.questions
            << " questions over the map's " << linked.drives << " drives: " << linked.new_links
            << " place links added (place links of the map: " << map.placeLinks().size() << ")\n";
}

int run(int argc, char** argv) {
  std::optional<BuildOptions> parsed = parseOptions(argc, argv);
  if (!parsed) return 0;
  BuildOptions& options = *parsed;
  std::string& output = options.output;
  // A link names the map it points to, also one not written yet: the new map replaces that file, not
  // the link, and that file must be no input.
  if (std::filesystem::is_symlink(output)) output = mrs_vpr::tools::linkTarget("--output", output);
  mrs_vpr::tools::requireApartFromInputs({"--output", output},
                                         {{"--images", options.images}, {"--bag", options.bag_path}});
  // The output is checked before any work: a folder would otherwise be found only when the finished
  // map is renamed to it.
  if (std::filesystem::is_directory(output)) {
    throw std::invalid_argument("'" + output + "' is a folder; --output names the map file to write (e.g. " +
                                (std::filesystem::path(output) / "map.db").string() + ")");
  }
  mrs_vpr::tools::requireNoSpecialFile("--output", output);
  const bool exists = std::filesystem::exists(output);
  if (exists && !options.append && !options.force && !options.link_places) {
    throw std::invalid_argument("'" + output + "' exists; use --append to extend it or --force to replace it");
  }
  if (!exists && options.link_places) {
    throw std::invalid_argument("--link-places: there is no map '" + output + "' to link");
  }
  // A mistyped map name would otherwise become a second map, and the map meant would stay as it was.
  if (!exists && options.append) {
    throw std::invalid_argument("--append: there is no map '" + output + "' to extend (leave --append out to create it)");
  }
  // Its folder, a name the file system allows, and no earlier map's log beside it.
  if (!exists) mrs_vpr::MapDatabase::checkSaveTarget(output);
  // A map a node is writing is not replaced (the node would go on writing the old file), and none
  // starts writing it until the new map has taken its place (its frames would be lost).
  std::optional<mrs_vpr::MapHold> hold;
  if (exists) hold.emplace(output);
  // A map is extended with its own front end and keyframing, unless the command line names them (a
  // front end must be the same).
  const bool extends = exists && (options.append || options.link_places);
  if (extends) {
    const mrs_vpr::MapDatabase extended(output, mrs_vpr::MapAccess::kReadOnly);
    // Read here, where a damaged record is named by the map's own path rather than by its copy's.
    extended.placeLinks();
    extended.driveStarts();
    if (!options.descriptor_given) options.params = extended.descriptorParams();
    const std::optional<mrs_vpr::MapTraversal>& traversal = extended.traversal();
    if (!options.min_appearance_change_given && traversal && traversal->min_appearance_change) {
      options.min_appearance_change = *traversal->min_appearance_change;
    }
  }
  // Reads the bag's poses before anything is written, so that a bag without /tf leaves no file.
  std::optional<mrs_vpr::bag::BagKeyframes> keyframes;
  if (options.travel.min_travel != 0.0) keyframes.emplace(options.bag_path, options.travel);

  // Every map is built aside and renamed when complete; an extended one starts as a copy of the map,
  // which is read, never written (an older format is converted in the copy), and held meanwhile. A
  // failure leaves the map as it was.
  const std::string target = output + ".part";
  // Another build_map writing the same map: its unfinished file is not ours to remove.
  mrs_vpr::MapDatabase::checkNotHeld(target);
  const auto removePart = [&] {
    // Also what backupTo() writes for an extended map, target + ".part", should it have stopped.
    for (const std::string& file : {target, target + ".part"}) {
      std::error_code ignored;
      std::filesystem::remove(file, ignored);
      mrs_vpr::MapDatabase::removeCompanions(file);
    }
  };
  mrs_vpr::MapDatabase::removeUnfinished(target, output);
  mrs_vpr::tools::catchInterruptions();
  bool own_part = false;  // Until then, a failure may be another run's: its files are left alone.
  try {
    if (extends) {
      mrs_vpr::MapDatabase(output, options.params, mrs_vpr::MapAccess::kReadOnly).backupTo(target);
      own_part = true;
    }
    // Made by this run if it was not there (even when opening it then fails, a full disk say).
    own_part = own_part || !std::filesystem::exists(target);
    mrs_vpr::MapDatabase map(target, options.params);
    own_part = true;
    if (options.link_places) {
      linkMapDrives(map, options);
    } else {
      addTraversal(map, options, keyframes);
    }
  } catch (...) {
    if (own_part) removePart();
    throw;
  }
  // The old map's log would be read into the new file (its frames are in the copy extended), and the
  // new file takes the old one's permissions: a private map stays private.
  if (exists) {
    mrs_vpr::MapDatabase::removeCompanions(output);
    std::error_code unknown;
    const std::filesystem::file_status old_map = std::filesystem::status(output, unknown);
    if (!unknown) std::filesystem::permissions(target, old_map.permissions(), unknown);
  }
  std::error_code error;
  std::filesystem::rename(target, output, error);
  hold.reset();
  if (error) {
    removePart();
    throw std::runtime_error("cannot replace '" + output + "' by the new map: " + error.message());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return mrs_vpr::tools::runTool("build_map", run, argc, argv); }
