#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "mrs_vpr/evaluation/drive_file.hpp"
#include "support/error_message.hpp"

namespace mrs_vpr {
namespace {

namespace fs = std::filesystem;
using testing_support::invalidArgumentMessage;

/// A file of this test's own under the system's temporary directory, removed when the test ends.
class DriveFileTest : public ::testing::Test {
 protected:
  DriveFileTest()
      : path_(fs::temp_directory_path() / ("mrs_vpr_drive_file_test_" + std::to_string(::getpid()) + ".csv")) {}
  ~DriveFileTest() override {
    std::error_code ignored;
    fs::remove(path_, ignored);
  }
  std::string write(const std::string& text) const {
    std::ofstream(path_) << text;
    return path_.string();
  }
  std::string path() const { return path_.string(); }

 private:
  fs::path path_;
};

TEST_F(DriveFileTest, ADriveComesBackAsWritten) {
  CameraDriveSettings settings;
  settings.stops = 2;
  settings.stop_frames_min = 3;
  settings.stop_frames_max = 4;
  settings.slow_frames = 5;
  settings.fast_frames = 6;
  const CameraDrive drive(40, settings);
  writeDriveFile(path(), drive.frames(), 100);
  const std::vector<DriveFrame> read = readDriveFile(path());
  ASSERT_EQ(read.size(), drive.frames().size());
  for (std::size_t i = 0; i < read.size(); ++i) {
    EXPECT_EQ(read[i].route_frame, drive.frames()[i].route_frame + 100);
    EXPECT_EQ(read[i].kind, drive.frames()[i].kind);
  }
  std::ifstream file(path());
  std::string header;
  std::getline(file, header);
  EXPECT_EQ(header, "drive_frame,route_frame,kind");
}

TEST_F(DriveFileTest, ABadFileIsNamedWithItsLine) {
  EXPECT_NE(invalidArgumentMessage([&] { readDriveFile(write("frame,route\n")); })
                .find(":1: expected the header 'drive_frame,route_frame,kind', got 'frame,route'"),
            std::string::npos);
  EXPECT_NE(invalidArgumentMessage([&] {
              readDriveFile(write("drive_frame,route_frame,kind\n0,4,moving\n2,5,moving\n"));
            }).find(":3: expected drive frame 1, got '2'"),
            std::string::npos);
  EXPECT_NE(invalidArgumentMessage([&] { readDriveFile(write("drive_frame,route_frame,kind\n0,-4,moving\n")); })
                .find(":2: route frame '-4' is not a non-negative integer"),
            std::string::npos);
  EXPECT_NE(invalidArgumentMessage([&] { readDriveFile(write("drive_frame,route_frame,kind\n0,4,parked\n")); })
                .find(":2: unknown drive frame kind 'parked'"),
            std::string::npos);
  EXPECT_NE(invalidArgumentMessage([&] { readDriveFile(write("drive_frame,route_frame,kind\n0 4 moving\n")); })
                .find(":2: expected 'drive_frame,route_frame,kind', got '0 4 moving'"),
            std::string::npos);
  EXPECT_NE(invalidArgumentMessage([&] { readDriveFile(write("")); }).find("the file is empty"), std::string::npos);
  EXPECT_THROW(readDriveFile(path() + ".missing"), std::runtime_error);
  // Windows line ends are read as well.
  EXPECT_EQ(readDriveFile(write("drive_frame,route_frame,kind\r\n0,7,stopped\r\n")).at(0).route_frame, 7);
}

}  // namespace
}  // namespace mrs_vpr
