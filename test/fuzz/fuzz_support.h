// Helpers shared by the fuzz targets: reading typed values from the input bytes, and a
// per-process scratch directory for the targets whose code under test reads files.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include <dirent.h>
#include <unistd.h>

namespace amha {
namespace fuzz {

/// Consumes the input front to back; past the end every read returns zeros.
struct Bytes {
  const std::uint8_t* p;
  std::size_t n;
  std::uint8_t u8() {
    if (n == 0) return 0;
    --n;
    return *p++;
  }
  std::uint16_t u16() { return static_cast<std::uint16_t>(u8() | (u8() << 8)); }
  std::uint32_t u32() {
    return static_cast<std::uint32_t>(u16()) | (static_cast<std::uint32_t>(u16()) << 16);
  }
  std::int32_t i32() {
    const std::uint32_t v = u32();
    std::int32_t out;
    std::memcpy(&out, &v, sizeof out);
    return out;
  }
  /// Any double, NaN and infinities included.
  double f64() {
    std::uint64_t v = u32();
    v |= static_cast<std::uint64_t>(u32()) << 32;
    double out;
    std::memcpy(&out, &v, sizeof out);
    return out;
  }
  /// A "reasonable" double: k / 16 for a signed byte k, or (rarely) an arbitrary one.
  double small(double scale) {
    const std::uint8_t sel = u8();
    if (sel == 255) return f64();
    return scale * static_cast<std::int8_t>(u8()) / 16.0;
  }
};

/// A directory of its own under /tmp, removed (with the files put in it) at exit.
inline const std::string& scratchDir() {
  static const std::string dir = [] {
    char tmpl[] = "/tmp/amha_fuzz_XXXXXX";
    const char* d = mkdtemp(tmpl);
    if (d == nullptr) std::abort();
    static std::string path;
    path = d;
    std::atexit([] {
      if (DIR* dp = opendir(path.c_str())) {
        while (const dirent* e = readdir(dp)) {
          if (std::strcmp(e->d_name, ".") != 0 && std::strcmp(e->d_name, "..") != 0) {
            std::remove((path + "/" + e->d_name).c_str());
          }
        }
        closedir(dp);
      }
      rmdir(path.c_str());
    });
    return path;
  }();
  return dir;
}

/// Writes bytes to scratchDir()/name and returns the path.
inline std::string writeScratch(const std::string& name, const void* data, std::size_t size) {
  const std::string path = scratchDir() + "/" + name;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) std::abort();
  if (size > 0 && std::fwrite(data, 1, size, f) != size) std::abort();
  std::fclose(f);
  return path;
}

/// Fails the run with a message (a finding, not a rejected input).
[[noreturn]] inline void finding(const std::string& what) {
  std::fprintf(stderr, "FUZZ FINDING: %s\n", what.c_str());
  std::abort();
}

}  // namespace fuzz
}  // namespace amha
