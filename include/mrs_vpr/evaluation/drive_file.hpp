#pragma once

#include <string>
#include <vector>

#include "mrs_vpr/evaluation/camera_drive.hpp"

namespace mrs_vpr {

/// The file beside a drive's images that names the route frame of each (make_drive writes it).
inline constexpr const char* kDriveFileName = "drive.csv";

/**
 * Writes `frames` as CSV: the header `drive_frame,route_frame,kind`, then one row per drive frame
 * `i,r,kind` (kind: moving, stopped or slow), with `first_route_frame` added to each route frame, so
 * that a drive of part of a folder names the folder's frames.
 * Throws std::runtime_error when the file cannot be written.
 */
void writeDriveFile(const std::string& path, const std::vector<DriveFrame>& frames, int first_route_frame = 0);

/**
 * Reads such a file: the drive's frames in order (route frame and kind; the stop fields are not kept).
 * Throws std::runtime_error when it cannot be opened and std::invalid_argument naming the file and line
 * for a bad header, a row out of order, a malformed or negative number or an unknown kind.
 */
std::vector<DriveFrame> readDriveFile(const std::string& path);

}  // namespace mrs_vpr
