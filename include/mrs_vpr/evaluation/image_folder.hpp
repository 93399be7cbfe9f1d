#pragma once

#include <functional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/evaluation/evaluation.hpp"

namespace mrs_vpr {

/**
 * Image files (png, jpg, jpeg, bmp, tif, tiff, pgm, ppm, pnm, pbm, webp, jp2, gif; any letter case) of
 * a folder, as full paths in file-name order, a run of digits counting as its number (frame2.png before
 * frame10.png; zero-padded names sort as they do byte by byte) and digits after a decimal point as a
 * fraction (1614000000.05.png before 1614000000.1.png).
 * Other files and folders are left out; `left_out`, when given, receives the names of the files, in
 * file-name order, so that a caller can say so (an image of another extension would be missing from
 * the frames). Throws std::runtime_error when the folder does not exist, is not a folder or holds no
 * image (naming the files it holds), and naming the entry when one named as an image is a broken
 * symbolic link, a folder or not a regular file (left out, it would shift every later frame's number).
 */
std::vector<std::string> listImageFiles(const std::string& folder, std::vector<std::string>* left_out = nullptr);

/// What a tool says when the files listImageFiles() returned are in another order than if the digits
/// after a point counted as numbers (cam1.9.png, cam1.10.png: unpadded counters, not fractions); empty
/// when both orders agree.
std::string fractionOrderNote(const std::vector<std::string>& files);

/// What a tool says of the files listImageFiles() left out of `folder` ("left out 2 files of 'F' not
/// named as an image (a.csv, b.jfif)"); empty when none was.
std::string leftOutNote(const std::string& folder, const std::vector<std::string>& left_out);

/// Reads one image with cv::IMREAD_UNCHANGED. Throws std::runtime_error naming the file and why when
/// unreadable (no permission, empty, no decoder), or a JPEG file cut short (which OpenCV would read,
/// grey where it is cut).
cv::Mat loadImage(const std::string& path);

/**
 * Loads the images of a folder one at a time in file-name order and hands each to `visit` (index,
 * path, image), so that a large folder never has to fit in memory.
 * Throws std::runtime_error as listImageFiles and loadImage do, and when an image's size differs from
 * the first one's (naming both files and sizes).
 */
void forEachImage(const std::string& folder,
                  const std::function<void(int index, const std::string& path, const cv::Mat& image)>& visit);

/// All images of a folder (see forEachImage).
std::vector<cv::Mat> loadImageFolder(const std::string& folder);

/**
 * Reads a ground-truth CSV: the header `query_index,matching_ref_indices`, then one row per query
 * frame `i,a b c` (0-based; the reference frames showing the same place, separated by spaces; none
 * allowed). Blank lines are skipped; Windows line ends are accepted.
 * Throws std::runtime_error when the file cannot be opened and std::invalid_argument naming the file
 * and line for a bad header, a malformed or negative index, or a query listed twice.
 */
GroundTruth readGroundTruthCsv(const std::string& path);

}  // namespace mrs_vpr
