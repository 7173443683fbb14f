// libamha_image_codecs.so: the only code of amha_planner that links opencv_imgcodecs.
// Debian's imgcodecs pulls in ~140 shared libraries (GDAL, poppler, HDF5, ICU, ...), ~48 MB of
// RSS and tens of ms of start-up; planner processes dlopen this module only when they really
// read or write an image file (see include/amha_planner/lattice/image_file.h, the loader).
// C ABI, so that nothing but these two symbols is looked up; no exception crosses it.
// Both sides link the same libopencv_core, so a cv::Mat may be passed by pointer.
#include <cstdio>
#include <new>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "image_codecs_abi.h"

namespace {

void copyMessage(const char* what, char* error, std::size_t error_size) {
  if (error != nullptr && error_size > 0) std::snprintf(error, error_size, "%s", what);
}

}  // namespace

extern "C" __attribute__((visibility("default"))) int AMHA_IMAGE_CODECS_READ(
    const char* path, int mode, cv::Mat* out, char* error, std::size_t error_size) noexcept {
  try {
    const int flags = mode == kAmhaImageReadGrey ? cv::IMREAD_GRAYSCALE : cv::IMREAD_UNCHANGED;
    *out = cv::imread(path, flags);
    return out->empty() ? kAmhaImageCodecsUnreadable : kAmhaImageCodecsOk;
  } catch (const std::bad_alloc&) {
    return kAmhaImageCodecsOutOfMemory;
  } catch (const std::exception& e) {  // cv::Exception, e.g. OpenCV's own size limit
    copyMessage(e.what(), error, error_size);
    return kAmhaImageCodecsError;
  } catch (...) {
    copyMessage("unknown exception in OpenCV", error, error_size);
    return kAmhaImageCodecsError;
  }
}

extern "C" __attribute__((visibility("default"))) int AMHA_IMAGE_CODECS_WRITE(
    const char* path, const cv::Mat* image, char* error, std::size_t error_size) noexcept {
  try {
    return cv::imwrite(path, *image) ? kAmhaImageCodecsOk : kAmhaImageCodecsUnwritable;
  } catch (const std::bad_alloc&) {
    return kAmhaImageCodecsOutOfMemory;
  } catch (const std::exception& e) {  // e.g. no writer for the file's extension
    copyMessage(e.what(), error, error_size);
    return kAmhaImageCodecsError;
  } catch (...) {
    copyMessage("unknown exception in OpenCV", error, error_size);
    return kAmhaImageCodecsError;
  }
}
