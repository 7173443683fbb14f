// Moving AI benchmark maps (.map): a header, then rows of characters, top row first.
#include <cmath>
#include <fstream>
#include <sstream>

#include "amha_planner/lattice/map_loaders.h"

namespace amha {
namespace lattice {

namespace {

[[noreturn]] void fail(const std::string& file, int line, const std::string& what) {
  std::ostringstream m;
  m << file;
  if (line > 0) m << ":" << line;
  m << ": " << what;
  throw LatticeError(LatticeError::Kind::kMap, m.str());
}

bool getLine(std::istream& in, std::string& s, int& line) {
  if (!std::getline(in, s)) return false;
  ++line;
  if (!s.empty() && s.back() == '\r') s.pop_back();
  return true;
}

// "key value" header line.
int headerValue(std::istream& in, const std::string& file, int& line, const char* key) {
  std::string s;
  if (!getLine(in, s, line)) fail(file, line + 1, std::string("missing '") + key + "' line");
  std::istringstream ls(s);
  std::string k;
  long v = 0;
  if (!(ls >> k >> v) || k != key)
    fail(file, line, std::string("expected '") + key + " N', found '" + s + "'");
  if (v <= 0 || v > 1000000)
    fail(file, line, std::string(key) + " " + std::to_string(v) + " is not in 1..1000000");
  return static_cast<int>(v);
}

}  // namespace

GridMap loadMovingAiMap(const std::string& file, double resolution, int upscale) {
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    fail(file, 0, "the resolution must be positive (Moving AI maps have no scale: choose one)");
  }
  if (upscale < 1 || upscale > 64)
    fail(file, 0, "upscale factor " + std::to_string(upscale) + " is not in 1..64");
  std::ifstream in(file);
  if (!in) fail(file, 0, "cannot open the file");
  int line = 0;
  std::string s;
  if (!getLine(in, s, line)) fail(file, 1, "empty file");
  {
    std::istringstream ls(s);
    std::string k, v;
    if (!(ls >> k >> v) || k != "type")
      fail(file, line, "expected 'type octile', found '" + s + "'");
  }
  const int h = headerValue(in, file, line, "height");
  const int w = headerValue(in, file, line, "width");
  if (!getLine(in, s, line) || s != "map") fail(file, line, "expected 'map'");
  const std::size_t cells =
      static_cast<std::size_t>(w) * upscale * static_cast<std::size_t>(h) * upscale;
  if (cells > (std::size_t{1} << 26)) {
    fail(file, 0, "upscaled map would have " + std::to_string(cells) + " cells (limit 2^26)");
  }
  GridMap map;
  map.width = w * upscale;
  map.height = h * upscale;
  map.resolution = resolution;
  map.cost.assign(cells, kFreeCost);
  for (int r = 0; r < h; ++r) {
    if (!getLine(in, s, line))
      fail(file, line + 1, "missing map row " + std::to_string(r + 1) + " of " + std::to_string(h));
    if (static_cast<int>(s.size()) != w) {
      fail(file, line,
           "row has " + std::to_string(s.size()) + " characters, width is " + std::to_string(w));
    }
    const int y0 = (h - 1 - r) * upscale;  // file row 0 is the top of the map
    for (int c = 0; c < w; ++c) {
      std::uint8_t cost;
      switch (s[c]) {
        case '.':
        case 'G':
        case 'S':
          cost = kFreeCost;
          break;
        case '@':
        case 'O':
        case 'T':
        case 'W':
          cost = kLethalCost;
          break;
        default:
          fail(file, line,
               std::string("unknown terrain character '") + s[c] + "' in column " +
                   std::to_string(c + 1));
      }
      if (cost == kFreeCost) continue;
      for (int dy = 0; dy < upscale; ++dy) {
        std::uint8_t* row = &map.cost[static_cast<std::size_t>(y0 + dy) * map.width];
        for (int dx = 0; dx < upscale; ++dx) row[c * upscale + dx] = cost;
      }
    }
  }
  while (getLine(in, s, line)) {
    if (s.find_first_not_of(" \t") != std::string::npos)
      fail(file, line, "unexpected text after the last map row");
  }
  return map;
}

}  // namespace lattice
}  // namespace amha
