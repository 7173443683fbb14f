// Image files (PNG, PGM, ...) for the lattice layer and the tools, through OpenCV's imgcodecs.
// imgcodecs is not linked into the libraries: on Debian it drags in ~140 shared libraries
// (GDAL, poppler, HDF5, ICU, ...) that cost every process ~48 MB of RSS, though planners fed
// by .cfg files or OccupancyGrid messages never read an image. These functions dlopen the
// module libamha_image_codecs.so on first use (once per process, thread-safe) from the
// directory of the library or executable that contains this code (build tree, catkin devel or
// install space), or from its ../lib; AMHA_IMAGE_CODECS_MODULE (a file path) overrides that.
#pragma once

#include <stdexcept>
#include <string>

#include <opencv2/core/mat.hpp>

namespace amha {
namespace lattice {

/// The module could not be loaded: "cannot load image codecs module <path>: <dlerror()>".
class ImageCodecsUnavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class ImageReadMode {
  kAsIs,  ///< channels and depth as stored (cv::IMREAD_UNCHANGED)
  kGrey,  ///< 8-bit, one channel (cv::IMREAD_GRAYSCALE)
};

/// cv::imread: an empty Mat if the file is missing or not in a format OpenCV reads. Throws
/// std::runtime_error with OpenCV's message when OpenCV throws (e.g. its size limit),
/// std::bad_alloc when out of memory, ImageCodecsUnavailable when the module cannot be loaded.
cv::Mat readImageFile(const std::string& path, ImageReadMode mode = ImageReadMode::kAsIs);

/// cv::imwrite (format from the extension). Throws std::runtime_error "cannot write <path>"
/// (with OpenCV's reason when it gives one), std::bad_alloc, ImageCodecsUnavailable.
void writeImageFile(const std::string& path, const cv::Mat& image);

/// The module file readImageFile/writeImageFile load (or would load), for diagnostics.
std::string imageCodecsModulePath();

}  // namespace lattice
}  // namespace amha
