// Loader of libamha_image_codecs.so (see image_file.h for why the codecs live in a module).
#include "amha_planner/lattice/image_file.h"

#include <dlfcn.h>
#include <link.h>
#include <unistd.h>

#include <climits>
#include <cstdlib>
#include <mutex>
#include <new>
#include <vector>

#include "image_codecs_abi.h"

namespace amha {
namespace lattice {

namespace {

constexpr const char* kModuleFile = "libamha_image_codecs.so";
constexpr const char* kOverrideVariable = "AMHA_IMAGE_CODECS_MODULE";

std::string directoryOf(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? std::string("/") : path.substr(0, slash);
}

// The shared library (or executable, when amha_lattice is linked statically) holding this code.
std::string ownObjectFile() {
  Dl_info info;
  link_map* map = nullptr;
  if (dladdr1(reinterpret_cast<void*>(&ownObjectFile), &info, reinterpret_cast<void**>(&map),
              RTLD_DL_LINKMAP) == 0) {
    return "";
  }
  if (map != nullptr && map->l_name != nullptr && map->l_name[0] != '\0') return map->l_name;
  // The main program has an empty link_map name (dladdr would give argv[0], maybe relative
  // or found through PATH): ask the kernel.
  char exe[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (n > 0) return std::string(exe, static_cast<std::size_t>(n));
  return info.dli_fname != nullptr ? info.dli_fname : "";
}

// Where to look, best first: the override, or next to the object holding this code and in
// its ../lib (executables in build/bin or build/tests, the module in build/lib), both for the
// path the dynamic linker used and for its target if that is a symbolic link.
std::vector<std::string> candidatePaths() {
  const char* override_path = std::getenv(kOverrideVariable);
  if (override_path != nullptr && override_path[0] != '\0') return {override_path};
  std::vector<std::string> dirs;
  const std::string object = ownObjectFile();
  if (!object.empty()) {
    dirs.push_back(directoryOf(object));
    char real[PATH_MAX];
    if (realpath(object.c_str(), real) != nullptr && directoryOf(real) != dirs[0]) {
      dirs.push_back(directoryOf(real));
    }
  }
  if (dirs.empty()) dirs.push_back(".");
  std::vector<std::string> paths;
  for (const auto& d : dirs) paths.push_back(d + "/" + kModuleFile);
  for (const auto& d : dirs) paths.push_back(d + "/../lib/" + kModuleFile);
  return paths;
}

struct Module {
  AmhaImageCodecsReadFn read = nullptr;
  AmhaImageCodecsWriteFn write = nullptr;
  std::string error;  ///< non-empty: the module could not be loaded
};

std::string dlerrorText() {
  const char* e = dlerror();
  return e != nullptr ? e : "unknown error";
}

Module loadModule() {
  // OpenCV refuses an image above OPENCV_IO_MAX_IMAGE_PIXELS before allocating it; the default,
  // 2^30, let a file of a few bytes whose header claims ~10^9 colour pixels make imread allocate
  // 3 GB (found by the map_server fuzzer). OpenCV reads the variable when its library loads, so
  // it is set here, before the module that links it is opened: 2^28 pixels, 16 times the
  // largest map the server takes (~max_map_cells); a value the user set is kept.
  setenv("OPENCV_IO_MAX_IMAGE_PIXELS", "268435456", 0);
  Module m;
  std::string error_path,
      error_text;  // the most useful failure: an existing file beats a missing one
  bool error_is_existing_file = false;
  for (const std::string& path : candidatePaths()) {
    // RTLD_NODELETE: OpenCV's libraries are not made to be unloaded.
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
    if (handle == nullptr) {
      const std::string why = dlerrorText();
      const bool exists = access(path.c_str(), F_OK) == 0;
      if (error_path.empty() || (exists && !error_is_existing_file)) {
        error_path = path;
        error_text = why;
        error_is_existing_file = exists;
      }
      continue;
    }
    void* read = dlsym(handle, AMHA_IMAGE_CODECS_STR(AMHA_IMAGE_CODECS_READ));
    void* write =
        read != nullptr ? dlsym(handle, AMHA_IMAGE_CODECS_STR(AMHA_IMAGE_CODECS_WRITE)) : nullptr;
    if (write == nullptr) {  // dlerror() names the missing symbol
      m.error = "cannot load image codecs module " + path + ": " + dlerrorText();
      return m;
    }
    m.read = reinterpret_cast<AmhaImageCodecsReadFn>(read);
    m.write = reinterpret_cast<AmhaImageCodecsWriteFn>(write);
    return m;
  }
  m.error = "cannot load image codecs module " + error_path + ": " + error_text;
  return m;
}

const Module& module() {
  static std::once_flag once;
  static Module m;
  std::call_once(once, [] { m = loadModule(); });
  if (!m.error.empty()) throw ImageCodecsUnavailable(m.error);
  return m;
}

}  // namespace

cv::Mat readImageFile(const std::string& path, ImageReadMode mode) {
  const Module& m = module();
  cv::Mat image;
  char error[1024] = "";
  const int mode_code = mode == ImageReadMode::kGrey ? kAmhaImageReadGrey : kAmhaImageReadAsIs;
  switch (m.read(path.c_str(), mode_code, &image, error, sizeof error)) {
    case kAmhaImageCodecsOk:
      return image;
    case kAmhaImageCodecsUnreadable:
      return cv::Mat();
    case kAmhaImageCodecsOutOfMemory:
      throw std::bad_alloc();
    default:
      throw std::runtime_error(error[0] != '\0' ? std::string(error)
                                                : "OpenCV cannot read " + path);
  }
}

void writeImageFile(const std::string& path, const cv::Mat& image) {
  const Module& m = module();
  char error[1024] = "";
  switch (m.write(path.c_str(), &image, error, sizeof error)) {
    case kAmhaImageCodecsOk:
      return;
    case kAmhaImageCodecsOutOfMemory:
      throw std::bad_alloc();
    case kAmhaImageCodecsError:
      throw std::runtime_error("cannot write " + path + ": " + error);
    default:
      throw std::runtime_error("cannot write " + path);
  }
}

std::string imageCodecsModulePath() {
  const std::vector<std::string> paths = candidatePaths();
  for (const auto& p : paths) {
    if (access(p.c_str(), F_OK) == 0) return p;
  }
  return paths.front();
}

}  // namespace lattice
}  // namespace amha
