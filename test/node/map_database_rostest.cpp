// The node with a map database (~database), started and stopped by the test itself under rostest's
// master: restarts, kill -9, ~save_map, ~load_map, ~reset, bad databases at start-up, and a map built
// by the node against one built offline by build_map from the same frames.

#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <filesystem>
#include <fstream>
#include <random>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <std_srvs/Trigger.h>

#include "mrs_vpr/LoadMap.h"
#include "mrs_vpr/LoopClosure.h"
#include "mrs_vpr/MapInfo.h"
#include "mrs_vpr/QuerySequence.h"
#include "mrs_vpr/RejectClosure.h"
#include "mrs_vpr/SaveMap.h"
#include "mrs_vpr/descriptor.hpp"
#include "mrs_vpr/node/bag_images.hpp"
#include "mrs_vpr/node/ros_stamp.hpp"
#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/store/map_database.hpp"
#include "support/format_one_map.hpp"
#include "support/map_info_watch.hpp"
#include "support/rostest_main.hpp"
#include "support/route_fixture.hpp"
#include "support/service_call.hpp"
#include "support/subscriber_wait.hpp"
#include "support/temporary_folder.hpp"
#include "support/topic_inbox.hpp"

namespace {

using mrs_vpr::testing_support::defaultRouteImages;

namespace fs = std::filesystem;

constexpr double kReferenceStart = 1000.0;  // stamp of reference frame 0 [s]
constexpr double kFramePeriod = 0.1;        // [s] between the stamps of published frames
constexpr int kTolerance = 5;               // frames
const char* const kTopic = "/map_test/image";

/// The exact stamp of reference frame i, as published.
mrs_vpr::Stamp referenceStamp(int i) { return mrs_vpr::node::stampOf(ros::Time(kReferenceStart + i * kFramePeriod)); }

sensor_msgs::ImagePtr referenceMessage(int i) {
  return mrs_vpr::bag::toImageMessage(defaultRouteImages().reference[static_cast<std::size_t>(i)], "bgr8",
                                      ros::Time(kReferenceStart + i * kFramePeriod), "camera",
                                      static_cast<std::uint32_t>(i));
}

/// An mrs_vpr_node process named `name`, its output in `log`.
class NodeProcess {
 public:
  NodeProcess(const std::string& name, const std::vector<std::string>& parameters, const std::string& log)
      : name_(name) {
    std::vector<std::string> arguments = {MRS_VPR_NODE_PATH, "__name:=" + name, std::string("image:=") + kTopic};
    for (const auto& parameter : parameters) arguments.push_back("_" + parameter);
    pid_ = fork();
    if (pid_ == 0) {
      const int out = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      dup2(out, STDOUT_FILENO);
      dup2(out, STDERR_FILENO);
      std::vector<char*> argv;
      for (auto& argument : arguments) argv.push_back(argument.data());
      argv.push_back(nullptr);
      execv(argv[0], argv.data());
      _exit(127);
    }
  }
  ~NodeProcess() {
    if (pid_ > 0 && running()) kill(pid_, SIGKILL);
    if (pid_ > 0) waitpid(pid_, nullptr, 0);
  }

  bool running() {
    if (exited_) return false;
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) == pid_) {
      exited_ = true;
      status_ = status;
      return false;
    }
    return true;
  }

  /// Waits up to `seconds` for the process to end; its exit code, or -1 when it did not end.
  int waitForExit(double seconds) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (running() && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    if (!exited_) return -1;
    return WIFEXITED(status_) ? WEXITSTATUS(status_) : 128 + WTERMSIG(status_);
  }

  /// Stops the node as Ctrl-C does; its exit code.
  int stop() {
    kill(pid_, SIGINT);
    return waitForExit(20.0);
  }
  void killHard() {
    kill(pid_, SIGKILL);
    waitForExit(10.0);
  }

  std::string service(const std::string& name) const { return "/" + name_ + "/" + name; }
  const std::string& name() const { return name_; }

 private:
  std::string name_;
  pid_t pid_ = -1;
  bool exited_ = false;
  int status_ = 0;
};

using mrs_vpr::testing_support::fileContents;
using mrs_vpr::testing_support::MapInfoWatch;
using mrs_vpr::testing_support::TopicInbox;


class MapDatabaseNodeTest : public ::testing::Test {
 protected:
  void SetUp() override { image_pub_ = nh_.advertise<sensor_msgs::Image>(kTopic, 1000); }
  std::string path(const std::string& name) const { return folder_.path(name); }

  /// Starts a node on `database` and waits until it serves ~query and is subscribed.
  /// With `every_frame`, each frame is a keyframe, so that a test can count map frames; else frames
  /// are kept by appearance change, as by default.
  std::unique_ptr<NodeProcess> startNode(const std::string& name, const std::string& database,
                                         const std::vector<std::string>& extra = {}, bool every_frame = true) {
    std::vector<std::string> parameters = {"database:=" + database, "image_queue_size:=1000",
                                           "map_info_rate:=20.0", "recent_exclusion:=50"};
    if (every_frame) parameters.push_back("min_appearance_change:=0.0");
    parameters.push_back("sequence/alignment:=causal");  // The route's answers are checked at the newest frame.
    parameters.insert(parameters.end(), extra.begin(), extra.end());
    auto node = std::make_unique<NodeProcess>(name, parameters, path(name + ".log"));
    EXPECT_TRUE(ros::service::waitForService(node->service("query"), ros::Duration(30.0)))
        << "the node did not start; its log:\n" << fileContents(path(name + ".log"));
    EXPECT_TRUE(mrs_vpr::testing_support::waitForSubscribers(image_pub_, 1, 20.0));
    return node;
  }

  /// Publishes reference frames [begin, end) quickly; the node's queue holds them all.
  void publishReference(int begin, int end) {
    for (int i = begin; i < end; ++i) {
      image_pub_.publish(referenceMessage(i));
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  }

  /// Publishes kRevisitFrames frames, later and in another numbering: kElsewhereFrames of ground the
  /// route does not hold, then the route's frames 100.. again (the same images: a day like the first).
  void publishRevisit() {
    const cv::Mat& like = defaultRouteImages().reference[0];
    cv::RNG rng(11);
    for (int i = 0; i < kRevisitFrames; ++i) {
      cv::Mat view = like;
      if (i < kElsewhereFrames) {
        view = cv::Mat(like.size(), like.type());
        rng.fill(view, cv::RNG::UNIFORM, 0, 256);
        cv::GaussianBlur(view, view, cv::Size(0, 0), 2.0);
      } else {
        view = defaultRouteImages().reference[static_cast<std::size_t>(revisitRouteFrame(i))];
      }
      image_pub_.publish(*mrs_vpr::bag::toImageMessage(view, "bgr8", ros::Time(kRevisitStart + i * kFramePeriod),
                                                       "camera", static_cast<std::uint32_t>(100000 + i)));
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  static constexpr int kElsewhereFrames = 60;
  static constexpr int kRevisitFrames = 260;
  static constexpr double kRevisitStart = 9000.0;  // stamp of the revisit's first frame [s]
  /// The route frame that revisit frame i shows; -1 for ground the route does not hold.
  static int revisitRouteFrame(int i) { return i < kElsewhereFrames ? -1 : 100 + i - kElsewhereFrames; }

  /// Publishes reference frames [begin, end) after a map of `begin` frames was loaded, and expects
  /// every closure continuous mode publishes to localise the newest keyframe (causal alignment) of a
  /// sequence that holds published frames only.
  void expectSequencesOfCameraKeyframesOnly(TopicInbox<mrs_vpr::LoopClosure>& closures, int begin, int end,
                                            MapInfoWatch& info,
                                            std::chrono::milliseconds interval = std::chrono::milliseconds(2)) {
    for (int i = begin; i < end; ++i) {
      image_pub_.publish(referenceMessage(i));
      std::this_thread::sleep_for(interval);
    }
    waitPersisted(info, static_cast<std::uint32_t>(end));
    const auto published = closures.waitForCount(1);
    ASSERT_FALSE(published.empty());
    for (const mrs_vpr::LoopClosure& closure : published) {
      const int oldest_localised = begin + static_cast<int>(closure.query_length) - 1;
      EXPECT_GE(closure.localised_keyframe_stamp.toSec(), kReferenceStart + oldest_localised * kFramePeriod - 1e-6)
          << "a sequence of " << closure.query_length << " keyframes reached into the loaded map";
    }
  }

  /// Waits until the node's map holds `frames` frames, all committed to its database.
  static void waitPersisted(MapInfoWatch& info, std::uint32_t frames) {
    ASSERT_TRUE(info.waitFor(
        [&](const mrs_vpr::MapInfo& m) { return m.frames == frames && m.frames_persisted == frames; }, 30.0))
        << "map_info: " << info.latest().frames << " frames, " << info.latest().frames_persisted
        << " persisted; expected " << frames;
  }

  /// Writes the map database `database` of reference frames [0, frames) through a node of its own, which
  /// then stops (`extra`: its parameters beyond startNode's).
  void mapReference(const std::string& database, int frames, const std::vector<std::string>& extra = {}) {
    auto mapper = startNode("mapper", database, extra);
    MapInfoWatch info(nh_, "/" + mapper->name());
    publishReference(0, frames);
    waitPersisted(info, static_cast<std::uint32_t>(frames));
    EXPECT_EQ(mapper->stop(), 0);
  }

  /// The node's answer to query frames [first, first + count) of the second traversal.
  static mrs_vpr::QuerySequence::Response query(const NodeProcess& node, int first, int count) {
    mrs_vpr::QuerySequence srv;
    for (int i = first; i < first + count; ++i) {
      srv.request.images.push_back(
          *mrs_vpr::bag::toImageMessage(defaultRouteImages().query[static_cast<std::size_t>(i)], "bgr8",
                                        ros::Time(9000.0 + i * kFramePeriod), "camera",
                                        static_cast<std::uint32_t>(i)));
    }
    srv.request.method = "seqslam";
    EXPECT_TRUE(mrs_vpr::testing_support::callService(node.service("query"), srv));
    return srv.response;
  }

  /// The first query frame that shows reference frame `reference` or a later one.
  static int queryFrameAt(int reference) {
    const auto& truth = defaultRouteImages().query_to_reference;
    for (std::size_t i = 0; i < truth.size(); ++i) {
      if (truth[i] >= reference) return static_cast<int>(i);
    }
    return -1;
  }

  static std::vector<mrs_vpr::StoredFrame> storedFrames(const std::string& file) {
    std::vector<mrs_vpr::StoredFrame> frames;
    mrs_vpr::MapDatabase(file, mrs_vpr::DescriptorParams{}, mrs_vpr::MapAccess::kReadOnly)
        .forEachFrame([&](const mrs_vpr::StoredFrame& frame) {
          frames.push_back({frame.descriptor.clone(), frame.stamp, frame.frame_id, frame.sequence});
        });
    return frames;
  }

  ros::NodeHandle nh_;
  ros::Publisher image_pub_;
  mrs_vpr::testing_support::TemporaryFolder folder_{"mrs_vpr_map_node_test"};
};

TEST_F(MapDatabaseNodeTest, ARestartedNodeKeepsItsMapAndAnswersAboutTheFirstPart) {
  const std::string database = path("map.db");
  {
    auto node = startNode("mapper", database);
    MapInfoWatch info(nh_, "/" + node->name());
    publishReference(0, 200);
    waitPersisted(info, 200);
    EXPECT_EQ(node->stop(), 0);
  }
  auto node = startNode("mapper", database);
  MapInfoWatch info(nh_, "/" + node->name());
  waitPersisted(info, 200);  // Loaded at start-up, before any frame arrives.
  publishReference(200, 300);
  waitPersisted(info, 300);

  // A stretch of the second traversal over reference frames mapped before the restart.
  const int first = queryFrameAt(60);
  const int last = first + 79;
  ASSERT_LT(defaultRouteImages().query_to_reference[static_cast<std::size_t>(last)], 200);
  auto response = query(*node, first, 80);
  ASSERT_TRUE(response.success) << response.message;
  EXPECT_NEAR(response.reference_index, defaultRouteImages().query_to_reference[static_cast<std::size_t>(last)],
              kTolerance);
  EXPECT_NEAR(response.reference_stamp.toSec(), kReferenceStart + response.reference_index * kFramePeriod, 1e-3);
  EXPECT_TRUE(response.accepted);
  // And one over frames mapped after it.
  const int later = queryFrameAt(210);
  response = query(*node, later, 60);
  ASSERT_TRUE(response.success) << response.message;
  EXPECT_NEAR(response.reference_index, defaultRouteImages().query_to_reference[static_cast<std::size_t>(later + 59)],
              kTolerance);
  EXPECT_EQ(node->stop(), 0);
}

TEST_F(MapDatabaseNodeTest, TheNodeAndBuildMapStoreTheSameMapFromTheSameFrames) {
  // The same 150 messages: written to a bag for build_map, published to the node; both keep the
  // keyframes their default rule (appearance change) chooses, and the same ones.
  {
    rosbag::Bag bag(path("frames.bag"), rosbag::bagmode::Write);
    for (int i = 0; i < 150; ++i) bag.write(kTopic, ros::Time(kReferenceStart + i * kFramePeriod), referenceMessage(i));
  }
  const std::string command = std::string(BUILD_MAP_PATH) + " --bag " + path("frames.bag") + " --topic " + kTopic +
                              " --output " + path("offline.db") + " > " + path("build_map.log") + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << fileContents(path("build_map.log"));

  // A name of its own: earlier tests' "mapper" left ~min_appearance_change 0 on the parameter server.
  auto node = startNode("keyframer", path("node.db"), {}, false);
  MapInfoWatch info(nh_, "/" + node->name());
  publishReference(0, 150);
  ASSERT_TRUE(info.waitFor(
      [](const mrs_vpr::MapInfo& m) {
        return m.frames_received == 150 && m.frames_persisted == m.frames && m.frames + m.frames_too_similar == 150;
      },
      30.0))
      << "map_info: " << info.latest().frames_received << " received, " << info.latest().frames << " frames, "
      << info.latest().frames_too_similar << " too similar, " << info.latest().frames_persisted << " persisted";
  EXPECT_EQ(node->stop(), 0);

  const auto offline = storedFrames(path("offline.db"));
  const auto online = storedFrames(path("node.db"));
  EXPECT_GT(offline.size(), 75U);  // The route's frames show distinct places: most are keyframes.
  ASSERT_EQ(online.size(), offline.size());
  for (std::size_t i = 0; i < offline.size(); ++i) {
    SCOPED_TRACE("frame " + std::to_string(i));
    ASSERT_EQ(offline[i].descriptor.total(), online[i].descriptor.total());
    EXPECT_EQ(std::memcmp(offline[i].descriptor.data, online[i].descriptor.data, offline[i].descriptor.total()), 0);
    EXPECT_EQ(offline[i].stamp, online[i].stamp);
  }
  EXPECT_EQ(online.front().frame_id, "camera");  // What the node knows of the camera is kept too.
}

TEST_F(MapDatabaseNodeTest, SaveLoadAndResetKeepTheDatabaseEqualToTheMap) {
  auto node = startNode("mapper", path("map.db"));
  MapInfoWatch info(nh_, "/" + node->name());
  publishReference(0, 120);
  waitPersisted(info, 120);

  mrs_vpr::SaveMap save;
  save.request.path = path("snapshot.db");
  ASSERT_TRUE(mrs_vpr::testing_support::callService(node->service("save_map"), save));
  EXPECT_TRUE(save.response.success) << save.response.message;
  EXPECT_EQ(save.response.frames, 120U);
  EXPECT_EQ(storedFrames(path("snapshot.db")).size(), 120U);
  // Saving over a file is refused, naming it; the file stays as it was.
  const std::string snapshot = fileContents(path("snapshot.db"));
  ASSERT_TRUE(mrs_vpr::testing_support::callService(node->service("save_map"), save));
  EXPECT_FALSE(save.response.success);
  EXPECT_NE(save.response.message.find(path("snapshot.db")), std::string::npos) << save.response.message;
  EXPECT_NE(save.response.message.find("exists"), std::string::npos) << save.response.message;
  EXPECT_EQ(fileContents(path("snapshot.db")), snapshot);
  // A relative path is the node's working directory's: the message names the file from the root.
  save.request.path = "mrs_vpr_relative_snapshot_" + std::to_string(::getpid()) + ".db";
  ASSERT_TRUE(mrs_vpr::testing_support::callService(node->service("save_map"), save));
  ASSERT_TRUE(save.response.success) << save.response.message;
  const std::size_t quote = save.response.message.find("'/");
  ASSERT_NE(quote, std::string::npos) << save.response.message;
  const std::string written = save.response.message.substr(quote + 1, save.response.message.size() - quote - 2);
  EXPECT_EQ(fs::path(written).filename(), save.request.path) << save.response.message;
  EXPECT_TRUE(fs::exists(written)) << written;
  fs::remove(written);
  // A relative path that leads nowhere says where it led (~/.ros under roslaunch, not where it was typed).
  mrs_vpr::LoadMap missing;
  missing.request.path = "mrs_vpr_no_such_map_" + std::to_string(::getpid()) + ".db";
  ASSERT_TRUE(mrs_vpr::testing_support::callService(node->service("load_map"), missing));
  EXPECT_FALSE(missing.response.success);
  EXPECT_NE(missing.response.message.find("there is no such file ('" + missing.request.path +
                                          "' is relative to the node's working folder: it names '/"),
            std::string::npos)
      << missing.response.message;

  // A file that is not a map: refused, naming it, and the map is kept.
  {
    std::ofstream notes(path("notes.db"));
    notes << "my notes, not a map\n";
  }
  mrs_vpr::LoadMap load;
  load.request.path = path("notes.db");
  ASSERT_TRUE(mrs_vpr::testing_support::callService(node->service("load_map"), load));
  EXPECT_FALSE(load.response.success);
  EXPECT_NE(load.response.message.find(path("notes.db")), std::string::npos) << load.response.message;
  EXPECT_NE(load.response.message.find("not a database"), std::string::npos) << load.response.message;
  EXPECT_NE(load.response.message.find("kept"), std::string::npos) << load.response.message;
  EXPECT_EQ(fileContents(path("notes.db")), "my notes, not a map\n");

  std_srvs::Trigger reset;
  ASSERT_TRUE(mrs_vpr::testing_support::callService(node->service("reset"), reset));
  EXPECT_TRUE(reset.response.success);
  EXPECT_NE(reset.response.message.find("cleared 120 frames from the map and from the database"), std::string::npos)
      << reset.response.message;
  waitPersisted(info, 0);

  load.request.path = path("snapshot.db");
  ASSERT_TRUE(mrs_vpr::testing_support::callService(node->service("load_map"), load));
  EXPECT_TRUE(load.response.success) << load.response.message;
  EXPECT_EQ(load.response.frames, 120U);
  waitPersisted(info, 120);
  publishReference(120, 140);
  waitPersisted(info, 140);
  EXPECT_EQ(node->stop(), 0);
  // The node's database mirrors the map: the loaded frames, then the new ones.
  const auto frames = storedFrames(path("map.db"));
  ASSERT_EQ(frames.size(), 140U);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(frames[i].stamp, referenceStamp(static_cast<int>(i))) << i;
  }
}

TEST_F(MapDatabaseNodeTest, AMapInMemoryKeepsItsFramesIdsAndNumbersThroughSaveAndLoad) {
  // A node without ~database saved "" and -1 for every frame, and an answer about a loaded map's frame
  // was stamped with the frame id of the camera instead of the map's.
  auto node = startNode("memory", "");
  MapInfoWatch info(nh_, "/" + node->name());
  publishReference(0, 120);
  ASSERT_TRUE(info.waitFor([](const mrs_vpr::MapInfo& m) { return m.frames == 120; }, 30.0));
  mrs_vpr::SaveMap save;
  save.request.path = path("snapshot.db");
  ASSERT_TRUE(mrs_vpr::testing_support::callService(node->service("save_map"), save));
  ASSERT_TRUE(save.response.success) << save.response.message;
  std::vector<mrs_vpr::StoredFrame> frames = storedFrames(path("snapshot.db"));
  ASSERT_EQ(frames.size(), 120U);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(frames[i].frame_id, "camera") << i;
    EXPECT_EQ(frames[i].sequence, static_cast<std::int64_t>(i)) << i;
  }

  // The same frames seen by another camera, loaded: an answer about one of them names that camera.
  for (mrs_vpr::StoredFrame& frame : frames) frame.frame_id = "left_camera";
  mrs_vpr::MapDatabase(path("left.db"), mrs_vpr::DescriptorParams{}).append(frames);
  mrs_vpr::LoadMap load;
  load.request.path = path("left.db");
  ASSERT_TRUE(mrs_vpr::testing_support::callService(node->service("load_map"), load));
  ASSERT_TRUE(load.response.success) << load.response.message;
  TopicInbox<mrs_vpr::LoopClosure> closures(nh_, "/" + node->name() + "/loop_closure");
  ASSERT_TRUE(closures.waitConnected());
  mrs_vpr::QuerySequence recent;
  recent.request.recent_frames = 10;
  ASSERT_TRUE(mrs_vpr::testing_support::callService(node->service("query"), recent));
  ASSERT_TRUE(recent.response.success) << recent.response.message;
  mrs_vpr::LoopClosure closure;
  const ros::Time localised = recent.response.localised_stamp;
  ASSERT_TRUE(closures.waitFor([&](const mrs_vpr::LoopClosure& m) { return m.header.stamp == localised; }, closure,
                               10.0));
  EXPECT_EQ(closure.header.frame_id, "left_camera");
  EXPECT_EQ(load.response.message.find("warning"), std::string::npos) << load.response.message;

  // A map kept at another appearance change than the node's: its keyframes lie on another scale than
  // the camera's, and the load says so.
  {
    mrs_vpr::MapDatabase other_scale(path("other_scale.db"), mrs_vpr::DescriptorParams{});
    other_scale.append(frames);
    mrs_vpr::MapTraversal traversal;
    traversal.frames = 120;
    traversal.min_appearance_change = 0.123;
    other_scale.setTraversal(traversal);
  }
  load.request.path = path("other_scale.db");
  ASSERT_TRUE(mrs_vpr::testing_support::callService(node->service("load_map"), load));
  ASSERT_TRUE(load.response.success) << load.response.message;
  EXPECT_NE(load.response.message.find(
                "; warning: the map's keyframes were kept at an appearance change of 0.123, and ~min_appearance_change is"),
            std::string::npos)
      << load.response.message;
  // Saved before any frame joins it, the loaded map is still that traversal's, and keeps its record.
  save.request.path = path("other_scale_again.db");
  ASSERT_TRUE(mrs_vpr::testing_support::callService(node->service("save_map"), save));
  ASSERT_TRUE(save.response.success) << save.response.message;
  const std::optional<mrs_vpr::MapTraversal> kept =
      mrs_vpr::MapDatabase(path("other_scale_again.db"), mrs_vpr::MapAccess::kReadOnly).traversal();
  ASSERT_TRUE(kept.has_value());
  EXPECT_EQ(kept->frames, 120);
  EXPECT_EQ(kept->min_appearance_change, 0.123);
  EXPECT_EQ(node->stop(), 0);
}

TEST_F(MapDatabaseNodeTest, AfterALoadContinuousModeAsksAboutNewKeyframesOnly) {
  mapReference(path("map.db"), 200);
  // A node in continuous mode that has mapped 100 frames of its own, and asked about them.
  auto node = startNode("watcher", path("watcher.db"), {"auto_query_period:=0.2"});
  MapInfoWatch info(nh_, "/" + node->name());
  TopicInbox<mrs_vpr::LoopClosure> closures(nh_, "/" + node->name() + "/loop_closure");
  ASSERT_TRUE(closures.waitConnected());
  publishReference(0, 100);
  waitPersisted(info, 100);
  ASSERT_FALSE(closures.waitForCount(1).empty());
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // the questions about those frames end

  // The loaded map's keyframes came from the file, not from the camera: no closure is published for them.
  closures.clear();
  mrs_vpr::LoadMap load;
  load.request.path = path("map.db");
  ASSERT_TRUE(mrs_vpr::testing_support::callService(node->service("load_map"), load));
  ASSERT_TRUE(load.response.success) << load.response.message;
  waitPersisted(info, 200);
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));  // five periods
  EXPECT_TRUE(closures.received().empty()) << closures.received().size() << " closures, the first about "
                                           << closures.received().front().localised_keyframe_stamp;
  // The camera's next keyframes are asked about, with sequences of the camera's keyframes only: one
  // reaching back into the loaded map would join two drives (causal alignment: each question
  // localises its sequence's newest keyframe).
  expectSequencesOfCameraKeyframesOnly(closures, 200, 240, info);
  // The same after a restart on the database, whose map is loaded at start-up. Frames come slowly,
  // so that questions are asked while the first sequence fills.
  EXPECT_EQ(node->stop(), 0);
  node = startNode("watcher", path("watcher.db"), {"auto_query_period:=0.2"});
  MapInfoWatch restarted(nh_, "/" + node->name());
  waitPersisted(restarted, 240);
  TopicInbox<mrs_vpr::LoopClosure> after_restart(nh_, "/" + node->name() + "/loop_closure");
  ASSERT_TRUE(after_restart.waitConnected());
  expectSequencesOfCameraKeyframesOnly(after_restart, 240, 280, restarted, std::chrono::milliseconds(20));
  EXPECT_EQ(node->stop(), 0);
}

// ~query {recent_frames: K} asks about the loaded map's newest frames, or about the camera's, but never
// about a sequence that joins the two: the junction of two drives is no place, and an accepted answer
// there would link it to one.
TEST_F(MapDatabaseNodeTest, RecentFramesNeverJoinALoadedMapToTheCamerasFirstKeyframes) {
  mapReference(path("map.db"), 200);
  auto node = startNode("asker", path("map.db"));
  MapInfoWatch info(nh_, "/" + node->name());
  mrs_vpr::QuerySequence recent;
  recent.request.recent_frames = 10;
  ASSERT_TRUE(mrs_vpr::testing_support::callService(node->service("query"), recent));
  EXPECT_TRUE(recent.response.success) << recent.response.message;  // the map's own last drive

  publishReference(0, 6);
  waitPersisted(info, 206);
  ASSERT_TRUE(mrs_vpr::testing_support::callService(node->service("query"), recent));
  EXPECT_FALSE(recent.response.success);
  EXPECT_EQ(recent.response.reference_index, -1);
  EXPECT_EQ(recent.response.message,
            "a test sequence of map frames [196, 206) runs across the start of a drive at frame 200 (a map was "
            "loaded, as by a node started on its database or ~load_map, or a visit appended, before it): the "
            "junction of two drives is no place; ask about at most 6 frames, or about 10 once the drive holds that "
            "many");
  recent.request.recent_frames = 6;
  ASSERT_TRUE(mrs_vpr::testing_support::callService(node->service("query"), recent));
  EXPECT_TRUE(recent.response.success) << recent.response.message;

  publishReference(6, 10);
  waitPersisted(info, 210);
  recent.request.recent_frames = 10;
  ASSERT_TRUE(mrs_vpr::testing_support::callService(node->service("query"), recent));
  EXPECT_TRUE(recent.response.success) << recent.response.message;
  EXPECT_NEAR(recent.response.reference_index, 9, 3) << "the camera's first keyframes revisit the map's first";
  EXPECT_EQ(node->stop(), 0);

  // The database recorded the junction: after a restart it is still no place.
  node = startNode("asker", path("map.db"));
  recent.request.recent_frames = 15;
  ASSERT_TRUE(mrs_vpr::testing_support::callService(node->service("query"), recent));
  EXPECT_FALSE(recent.response.success);
  EXPECT_EQ(recent.response.message.rfind("a test sequence of map frames [195, 210) runs across the start of a drive "
                                          "at frame 200",
                                          0),
            0U)
      << recent.response.message;
  EXPECT_EQ(node->stop(), 0);
}

// A node that maps as it drives closes the loops of a revisit, which link the visits' frames, so that a
// place it holds twice is no rival of itself: the links survive a restart and a saved and loaded map,
// and a closure that the back end refused (~reject_closure) is forgotten for good.
TEST_F(MapDatabaseNodeTest, TheVisitsItsClosuresLinkedStayLinkedAfterARestartAndALoad) {
  const std::string database = path("map.db");
  std::uint32_t linked = 0;
  {
    auto node = startNode("linker", database, {"auto_query_period:=0.2", "descriptor/type:=thumbnail"});
    MapInfoWatch info(nh_, "/" + node->name());
    TopicInbox<mrs_vpr::LoopClosure> closures(nh_, "/" + node->name() + "/loop_closure");
    ASSERT_TRUE(closures.waitConnected());
    publishReference(0, 300);
    waitPersisted(info, 300);
    publishRevisit();
    waitPersisted(info, 560);
    std::this_thread::sleep_for(std::chrono::milliseconds(1000));  // the last questions
    int accepted = 0;
    for (const mrs_vpr::LoopClosure& closure : closures.received()) accepted += closure.accepted ? 1 : 0;
    // Each accepted closure linked the keyframe it localised, a new one each time.
    const auto each_linked = [&](const mrs_vpr::MapInfo& m) {
      return m.frames_linked == static_cast<std::uint32_t>(accepted);
    };
    ASSERT_TRUE(info.waitFor(each_linked, 10.0))
        << info.latest().frames_linked << " frames linked, " << accepted << " closures accepted";
    EXPECT_GE(accepted, 10) << closures.received().size() << " closures";
    std::printf("[ figures  ] revisit: %zu closures, %d accepted, %u frames linked\n", closures.received().size(),
                accepted, info.latest().frames_linked);
    linked = info.latest().frames_linked;

    // The back end refuses one closure: its link goes, from the map and (after the restart below) its
    // database; asking again, or with no stamp, is refused with the map unchanged.
    const auto is_accepted = [](const mrs_vpr::LoopClosure& closure) { return closure.accepted; };
    const std::vector<mrs_vpr::LoopClosure> received = closures.received();
    const auto refused = std::find_if(received.begin(), received.end(), is_accepted);
    ASSERT_NE(refused, received.end());
    mrs_vpr::RejectClosure reject;
    reject.request.localised_keyframe_stamp = refused->localised_keyframe_stamp;
    reject.request.reference_index = refused->reference_index;
    ASSERT_TRUE(mrs_vpr::testing_support::callService(node->service("reject_closure"), reject));
    EXPECT_TRUE(reject.response.success) << reject.response.message;
    EXPECT_EQ(reject.response.links_forgotten, 1U);
    EXPECT_EQ(reject.response.frames_linked, linked - 1);
    // Each refusal names its reason and leaves the map's links as they are.
    const auto expect_refused = [&](const std::string& reason) {
      ASSERT_TRUE(mrs_vpr::testing_support::callService(node->service("reject_closure"), reject));
      EXPECT_FALSE(reject.response.success);
      EXPECT_NE(reject.response.message.find(reason), std::string::npos) << reject.response.message;
      EXPECT_EQ(reject.response.frames_linked, linked - 1);
    };
    expect_refused("forgotten already");
    reject.request.reference_index = 100000;
    expect_refused("the reference frame 100000 is not a frame of the map, which holds frames 0 to 559");
    reject.request.localised_keyframe_stamp = ros::Time();
    expect_refused("localised_keyframe_stamp is 0");
    --linked;
    EXPECT_EQ(node->stop(), 0);
  }
  auto node = startNode("linker", database, {"descriptor/type:=thumbnail"});
  MapInfoWatch info(nh_, "/" + node->name());
  ASSERT_TRUE(info.waitFor([&](const mrs_vpr::MapInfo& m) { return m.frames == 560; }, 30.0));
  EXPECT_EQ(info.latest().frames_linked, linked) << "after the restart";
  mrs_vpr::SaveMap save;
  save.request.path = path("linked_copy.db");
  ASSERT_TRUE(mrs_vpr::testing_support::callService(node->service("save_map"), save));
  ASSERT_TRUE(save.response.success) << save.response.message;
  EXPECT_EQ(node->stop(), 0);

  auto loader = startNode("loader", "", {"descriptor/type:=thumbnail"});
  MapInfoWatch loaded(nh_, "/" + loader->name());
  mrs_vpr::LoadMap load;
  load.request.path = path("linked_copy.db");
  ASSERT_TRUE(mrs_vpr::testing_support::callService(loader->service("load_map"), load));
  ASSERT_TRUE(load.response.success) << load.response.message;
  ASSERT_TRUE(loaded.waitFor([&](const mrs_vpr::MapInfo& m) { return m.frames == 560; }, 30.0));
  EXPECT_EQ(loaded.latest().frames_linked, linked) << "after ~load_map";
  EXPECT_EQ(loader->stop(), 0);
}

// A map built on an earlier drive, served with ~map_mode fixed: continuous mode localises the camera's
// keyframes in it, right, and the map and its database stay as they were.
TEST_F(MapDatabaseNodeTest, AFixedMapLocalisesTheCameraAndStaysAsItWas) {
  const std::string database = path("map.db");
  for (const auto& [file, frames] : {std::make_pair(database, 300), std::make_pair(path("small.db"), 40)}) {
    mapReference(file, frames, {"descriptor/type:=thumbnail"});
  }
  auto node = startNode("localiser", database,
                        {"descriptor/type:=thumbnail", "map_mode:=fixed", "auto_query_period:=0.2"});
  MapInfoWatch info(nh_, "/" + node->name());
  TopicInbox<mrs_vpr::LoopClosure> closures(nh_, "/" + node->name() + "/loop_closure");
  ASSERT_TRUE(closures.waitConnected());
  publishRevisit();
  ASSERT_TRUE(info.waitFor([](const mrs_vpr::MapInfo& m) { return m.frames_received == kRevisitFrames; }, 30.0));
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));  // the last questions
  int right = 0;
  for (const mrs_vpr::LoopClosure& closure : closures.received()) {
    if (!closure.accepted) continue;
    const int i =
        static_cast<int>(std::lround((closure.localised_keyframe_stamp.toSec() - kRevisitStart) / kFramePeriod));
    const int truth = revisitRouteFrame(i);
    EXPECT_GE(truth, 0) << "accepted on ground the map does not hold (revisit frame " << i << ")";
    EXPECT_NEAR(closure.reference_index, truth, kTolerance) << "revisit frame " << i;
    right += truth >= 0 && std::abs(closure.reference_index - truth) <= kTolerance ? 1 : 0;
  }
  // How many questions continuous mode asks depends on the machine (a fifth of each period); seen: 83 to 149.
  EXPECT_GE(right, 20) << closures.received().size() << " closures";
  // ~query {recent_frames} asks about the camera's newest keyframes, as continuous mode does.
  mrs_vpr::QuerySequence recent;
  recent.request.recent_frames = 20;
  ASSERT_TRUE(mrs_vpr::testing_support::callService(node->service("query"), recent));
  ASSERT_TRUE(recent.response.success) << recent.response.message;
  EXPECT_TRUE(recent.response.accepted) << recent.response.message;
  EXPECT_NEAR(recent.response.reference_index, 299, kTolerance);
  EXPECT_EQ(info.latest().frames, 300U);
  // The file is only read at start-up, and not held: other programs read it meanwhile.
  EXPECT_EQ(mrs_vpr::MapDatabase(database, mrs_vpr::MapAccess::kReadOnly).size(), 300);
  // ~load_map and ~reset change the map in memory only; the file stays as it was.
  const std::string before = fileContents(database);
  mrs_vpr::LoadMap load;
  load.request.path = path("small.db");
  ASSERT_TRUE(mrs_vpr::testing_support::callService(node->service("load_map"), load));
  ASSERT_TRUE(load.response.success) << load.response.message;
  EXPECT_EQ(load.response.message.find("database"), std::string::npos) << load.response.message;
  std_srvs::Trigger reset;
  ASSERT_TRUE(mrs_vpr::testing_support::callService(node->service("reset"), reset));
  ASSERT_TRUE(reset.response.success) << reset.response.message;
  EXPECT_NE(reset.response.message.find("the map file is left as it is"), std::string::npos) << reset.response.message;
  EXPECT_EQ(fileContents(database), before);
  EXPECT_EQ(node->stop(), 0);
  std::printf("[ figures  ] fixed map: %zu closures, %d accepted and right\n", closures.received().size(), right);

  // A fixed map must exist: a mistyped path stops the node, naming it, and creates no file.
  NodeProcess missing("missing", {"database:=" + path("no_such_map.db"), "map_mode:=fixed"}, path("missing.log"));
  EXPECT_EQ(missing.waitForExit(30.0), 1);
  const std::string log = fileContents(path("missing.log"));
  EXPECT_NE(log.find(path("no_such_map.db") + "': there is no such file"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(path("no_such_map.db")));
}

TEST_F(MapDatabaseNodeTest, KillNineAt30HzLosesNoFrameReportedPersisted) {
  // Frames at 30 Hz, default commits (1 s or 100 frames); the node is killed with SIGKILL at seeded
  // moments. Every frame ~map_info called persisted must be in the database afterwards.
  std::mt19937 rng(11);
  for (int round = 0; round < 3; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    const std::string database = path("crash" + std::to_string(round) + ".db");
    auto node = startNode("crasher" + std::to_string(round), database);
    MapInfoWatch info(nh_, "/" + node->name());
    const int frames = std::uniform_int_distribution<int>(60, 150)(rng);
    std::uint64_t reported = 0;
    for (int i = 0; i < frames; ++i) {
      image_pub_.publish(referenceMessage(i));
      reported = info.latest().frames_persisted;
      std::this_thread::sleep_for(std::chrono::microseconds(33333));
    }
    reported = info.latest().frames_persisted;
    node->killHard();
    const auto stored = storedFrames(database);
    std::printf("[ figures  ] kill -9 after %d frames at 30 Hz: %llu reported persisted, %zu in the database\n",
                frames, static_cast<unsigned long long>(reported), stored.size());
    EXPECT_GE(stored.size(), reported);
    EXPECT_GT(reported, 0U);
    // At most about one commit period (30 frames) and the frames in flight are lost.
    EXPECT_GE(static_cast<int>(stored.size()), frames - 45);
    for (std::size_t i = 0; i < stored.size(); ++i) {
      EXPECT_EQ(stored[i].stamp, referenceStamp(static_cast<int>(i))) << i;
    }
  }
}

TEST_F(MapDatabaseNodeTest, TheLatestRosTimeIsStoredServedAndLoadedExactly) {
  // {4294967295, 999999999} as seconds in a double is 4294967296.0, beyond ROS's range: the node
  // aborted ("Time is out of dual 32-bit range") once such a frame was in its map, and at every
  // later start, as the frame had been committed first.
  const ros::Time latest(4294967295U, 999999999U);
  {
    auto node = startNode("latest", path("map.db"));
    MapInfoWatch info(nh_, "/" + node->name());
    publishReference(0, 79);
    sensor_msgs::ImagePtr last = referenceMessage(79);
    last->header.stamp = latest;
    image_pub_.publish(last);
    waitPersisted(info, 80);
    EXPECT_EQ(info.latest().last_stamp, latest);
    // A stamp a message can carry but no time can hold (nanoseconds beyond a second, past the end):
    // a failed frame, and the node runs on.
    sensor_msgs::ImagePtr beyond = referenceMessage(0);
    beyond->header.stamp.sec = 4294967295U;
    beyond->header.stamp.nsec = 1999999999U;
    image_pub_.publish(beyond);
    ASSERT_TRUE(info.waitFor([](const mrs_vpr::MapInfo& m) { return m.frames_failed == 1; }, 20.0))
        << "frames failed: " << info.latest().frames_failed;
    EXPECT_EQ(info.latest().frames, 80U);
    // The newest frames as the test sequence: its newest stamp is the latest time.
    mrs_vpr::QuerySequence recent;
    recent.request.recent_frames = 10;
    ASSERT_TRUE(mrs_vpr::testing_support::callService(node->service("query"), recent));
    EXPECT_TRUE(recent.response.success) << recent.response.message;
    EXPECT_EQ(recent.response.localised_stamp, latest);  // Causal alignment: the newest frame is localised.
    // query_bag reports both stamps of its answer exactly, in nanoseconds.
    {
      rosbag::Bag bag(path("late.bag"), rosbag::bagmode::Write);
      for (int i = 60; i < 80; ++i) {
        sensor_msgs::ImagePtr frame = referenceMessage(i);
        if (i == 79) frame->header.stamp = latest;
        bag.write(kTopic, frame->header.stamp, frame);
      }
    }
    const std::string command = std::string(QUERY_BAG_PATH) + " --bag " + path("late.bag") + " --topic " + kTopic +
                                " --start 0 --count 20 --min-appearance-change 0 --method seqslam --service " +
                                node->service("query") + " > " +
                                path("answer.json") + " 2> " + path("query_bag.log");
    ASSERT_EQ(std::system(command.c_str()), 0) << fileContents(path("query_bag.log"));
    const nlohmann::json answer = nlohmann::json::parse(fileContents(path("answer.json")));
    EXPECT_EQ(answer.at("request").at("last_stamp_ns").get<std::int64_t>(), mrs_vpr::Stamp::kMaxNanoseconds);
    EXPECT_EQ(answer.at("method").get<std::string>(), "seqslam");  // The method that answered.
    EXPECT_GE(answer.at("query_length").get<int>(), mrs_vpr::kMinSequenceFrames);
    EXPECT_LE(answer.at("query_length").get<int>(), 20);
    EXPECT_GE(answer.at("threads").get<int>(), 1);
    const int index = answer.at("reference_index").get<int>();
    ASSERT_GE(index, 0);
    EXPECT_EQ(answer.at("reference_stamp_ns").get<std::int64_t>(),
              index == 79 ? mrs_vpr::Stamp::kMaxNanoseconds : referenceStamp(index).nanoseconds());
    EXPECT_TRUE(node->running());
    EXPECT_EQ(node->stop(), 0);
  }
  EXPECT_EQ(storedFrames(path("map.db")).back().stamp, mrs_vpr::node::stampOf(latest));
  auto node = startNode("latest", path("map.db"));
  MapInfoWatch info(nh_, "/" + node->name());
  waitPersisted(info, 80);
  EXPECT_EQ(info.latest().last_stamp, latest);

  EXPECT_EQ(node->stop(), 0);

  // A map that an earlier release committed with that frame (REAL 4294967296.0): refused, naming
  // the frame, by ~load_map and at start-up; the running node keeps its map. Such maps hold
  // thumbnails, so the nodes that read them describe frames so too.
  mrs_vpr::testing_support::writeFormatOneMap(path("old.db"), {1000.0, 4294967296.0});
  auto thumbnails = startNode("thumbnails", path("thumbnails.db"), {"descriptor/type:=thumbnail"});
  MapInfoWatch thumbnail_info(nh_, "/" + thumbnails->name());
  publishReference(0, 5);
  waitPersisted(thumbnail_info, 5);
  mrs_vpr::LoadMap load;
  load.request.path = path("old.db");
  ASSERT_TRUE(mrs_vpr::testing_support::callService(thumbnails->service("load_map"), load));
  EXPECT_FALSE(load.response.success);
  EXPECT_NE(load.response.message.find("frame 2 has an unusable stamp: stamp 4294967296 s is outside 0 .. "
                                       "4294967295.999999999 s, the range of a ROS time"),
            std::string::npos)
      << load.response.message;
  EXPECT_NE(load.response.message.find("the current map is kept"), std::string::npos) << load.response.message;
  EXPECT_TRUE(thumbnails->running());
  EXPECT_EQ(thumbnail_info.latest().frames, 5U);
  // query_bag chooses a bag's frames as this node keeps a camera's: by its front end, which it reads
  // from the node's parameters. (5 map frames answer no question: only the record counts.)
  const std::string ask = std::string(QUERY_BAG_PATH) + " --bag " + path("late.bag") + " --topic " + kTopic +
                          " --start 0 --count 4 --service " + thumbnails->service("query") + " > " +
                          path("thumbnail_answer.json") + " 2> " + path("thumbnail_query_bag.log");
  EXPECT_GE(std::system(ask.c_str()), 0);
  const std::string answer_text = fileContents(path("thumbnail_answer.json"));
  ASSERT_FALSE(answer_text.empty()) << fileContents(path("thumbnail_query_bag.log"));
  const nlohmann::json asked = nlohmann::json::parse(answer_text);
  EXPECT_EQ(asked.at("request").at("keyframing").get<std::string>(), "the parameters of /" + thumbnails->name());
  EXPECT_NE(asked.at("request").at("front_end").get<std::string>().find("thumbnail"), std::string::npos)
      << asked.dump();
  EXPECT_EQ(thumbnails->stop(), 0);
  NodeProcess old("old_map", {"database:=" + path("old.db"), "descriptor/type:=thumbnail"}, path("old_map.log"));
  EXPECT_EQ(old.waitForExit(30.0), 1);
  const std::string log = fileContents(path("old_map.log"));
  EXPECT_NE(log.find("frame 2 has an unusable stamp"), std::string::npos) << log;
}

TEST_F(MapDatabaseNodeTest, CtrlCEndsARunningQuestionInsteadOfWaitingForIt) {
  // The node's shutdown joins its query thread: it stops a running question first rather than wait
  // for it. A brute-force question about 2000 keyframes of 100k frames takes seconds.
  const std::string database = path("large.db");
  {
    const mrs_vpr::DescriptorParams params;
    const int size = mrs_vpr::DescriptorExtractor(params).size();
    cv::RNG random(5);
    std::vector<mrs_vpr::StoredFrame> frames;
    for (int i = 0; i < 100000; ++i) {
      cv::Mat descriptor(1, size, CV_8UC1);
      random.fill(descriptor, cv::RNG::UNIFORM, 0, 256);
      frames.push_back({descriptor, referenceStamp(i), "camera", i});
    }
    mrs_vpr::MapDatabase(database, params).append(frames);
  }
  auto node = startNode("stopper", database);
  mrs_vpr::QuerySequence whole;
  whole.request.recent_frames = 2000;
  whole.request.method = "seqslam";
  ASSERT_TRUE(mrs_vpr::testing_support::callService(node->service("query"), whole));
  ASSERT_TRUE(whole.response.success) << whole.response.message;
  const double question_s = whole.response.elapsed_ms / 1000.0;

  // The same question again, and Ctrl-C a second into it.
  mrs_vpr::QuerySequence stopped;
  stopped.request = whole.request;
  bool answered = false;
  std::thread asking([&] { answered = mrs_vpr::testing_support::callService(node->service("query"), stopped); });
  std::this_thread::sleep_for(std::chrono::seconds(1));
  const auto sigint = std::chrono::steady_clock::now();
  const int exit_code = node->stop();
  const double exit_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - sigint).count();
  asking.join();
  std::printf("[ figures  ] the question took %.1f s; Ctrl-C a second into it ended the node in %.1f s\n", question_s,
              exit_s);
  EXPECT_EQ(exit_code, 0);
  EXPECT_LT(exit_s, question_s - 1.0) << "the node waited for the question to end";
  if (answered) {  // The reply can be lost as the node's connections close.
    EXPECT_FALSE(stopped.response.success);
    EXPECT_NE(stopped.response.message.find("shutting down"), std::string::npos) << stopped.response.message;
  }
  EXPECT_EQ(storedFrames(database).size(), 100000U);
}

TEST_F(MapDatabaseNodeTest, AnUnusableDatabaseStopsTheNodeAtStartUpNamingIt) {
  {
    std::ofstream notes(path("notes.db"));
    notes << "my notes, not a map\n";
  }
  NodeProcess node("bad_db", {"database:=" + path("notes.db")}, path("bad_db.log"));
  EXPECT_EQ(node.waitForExit(30.0), 1);
  const std::string log = fileContents(path("bad_db.log"));
  EXPECT_NE(log.find(path("notes.db")), std::string::npos) << log;
  EXPECT_NE(log.find("not a database"), std::string::npos) << log;
  EXPECT_EQ(fileContents(path("notes.db")), "my notes, not a map\n");

  // A database another node holds.
  auto owner = startNode("owner", path("map.db"));
  NodeProcess second("second", {"database:=" + path("map.db")}, path("second.log"));
  EXPECT_EQ(second.waitForExit(30.0), 1);
  const std::string second_log = fileContents(path("second.log"));
  EXPECT_NE(second_log.find("locked by another process"), std::string::npos) << second_log;
  EXPECT_TRUE(owner->running());
  EXPECT_EQ(owner->stop(), 0);
}

}  // namespace

int main(int argc, char** argv) {
  return mrs_vpr::testing_support::runRostests(argc, argv, "mrs_vpr_map_database_rostest");
}
