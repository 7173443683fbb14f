// Helpers shared by the tile tests.
#pragma once

#include <cstdlib>
#include <string>

namespace amha {
namespace tiles {
namespace testing {

/// ../shared/data (from the build's AMHA_SHARED_DATA), or "" if absent.
inline std::string sharedData() {
  const char* d = std::getenv("AMHA_SHARED_DATA");
  return d != nullptr ? std::string(d) : std::string();
}

inline std::string korfFile() {
  const std::string d = sharedData();
  return d.empty() ? std::string() : d + "/tiles/korf100_15puzzle.txt";
}

}  // namespace testing
}  // namespace tiles
}  // namespace amha
