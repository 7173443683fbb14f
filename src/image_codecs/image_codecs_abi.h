// The C interface between libamha_image_codecs.so and its loader (src/lattice/image_file.cpp).
// The symbol names carry a version: a module from another build with a different interface is
// refused by dlsym instead of being called wrongly. Change the suffix when the interface changes.
#pragma once

#include <cstddef>

#define AMHA_IMAGE_CODECS_READ amha_image_codecs_read_v1
#define AMHA_IMAGE_CODECS_WRITE amha_image_codecs_write_v1
#define AMHA_IMAGE_CODECS_STR2(x) #x
#define AMHA_IMAGE_CODECS_STR(x) AMHA_IMAGE_CODECS_STR2(x)

namespace cv {
class Mat;
}

/// How to read: as stored (cv::IMREAD_UNCHANGED) or as 8-bit grey (cv::IMREAD_GRAYSCALE).
enum : int { kAmhaImageReadAsIs = 0, kAmhaImageReadGrey = 1 };

/// Results of both functions; only kAmhaImageCodecsError writes a message into `error`.
enum : int {
  kAmhaImageCodecsOk = 0,
  kAmhaImageCodecsUnreadable = 1,  ///< cv::imread returned an empty image (missing, unsupported)
  kAmhaImageCodecsUnwritable = 2,  ///< cv::imwrite returned false
  kAmhaImageCodecsError = 3,       ///< OpenCV threw; its message is in `error`
  kAmhaImageCodecsOutOfMemory = 4,
};

/// int read(const char* path, int mode, cv::Mat* out, char* error, size_t error_size)
using AmhaImageCodecsReadFn = int (*)(const char*, int, cv::Mat*, char*, std::size_t);
/// int write(const char* path, const cv::Mat* image, char* error, size_t error_size)
using AmhaImageCodecsWriteFn = int (*)(const char*, const cv::Mat*, char*, std::size_t);
