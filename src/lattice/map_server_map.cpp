// map_server's YAML + image maps, with map_server's exact semantics (see map_loaders.h).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include <yaml-cpp/yaml.h>
#include <opencv2/core.hpp>

#include "amha_planner/lattice/image_file.h"
#include "amha_planner/lattice/map_loaders.h"

namespace amha {
namespace lattice {

namespace {

[[noreturn]] void fail(const std::string& file, const std::string& what, int line = -1) {
  std::ostringstream m;
  m << file;
  if (line >= 0) m << ":" << line + 1;
  m << ": " << what;
  throw LatticeError(LatticeError::Kind::kMap, m.str());
}

double number(const YAML::Node& doc, const char* key, const std::string& file) {
  const YAML::Node n = doc[key];
  if (!n) fail(file, std::string("missing '") + key + "'");
  try {
    const double v = n.as<double>();
    if (!std::isfinite(v)) fail(file, std::string("'") + key + "' is not finite", n.Mark().line);
    return v;
  } catch (const YAML::Exception&) {
    fail(file, std::string("'") + key + "' is not a number", n.Mark().line);
  }
}

// The most cells gridMapFromOccupancy accepts by default (loadMapServerMap uses it).
constexpr std::uint64_t kMaxCells = std::uint64_t{1} << 26;

// Width and height from a PNG or PNM (PBM/PGM/PPM) header, without decoding: a small PNG can
// hold gigapixels, so a huge image is refused before OpenCV allocates it. False for other
// formats (OpenCV's own limit, 2^30 pixels, and the check after decoding apply to them).
bool headerSize(const std::string& path, std::uint64_t* w, std::uint64_t* h) {
  std::ifstream f(path, std::ios::binary);
  char b[512];
  f.read(b, sizeof b);
  const std::size_t n = static_cast<std::size_t>(f.gcount());
  auto be32 = [&](std::size_t i) {
    std::uint64_t v = 0;
    for (std::size_t k = 0; k < 4; ++k) v = (v << 8) | static_cast<unsigned char>(b[i + k]);
    return v;
  };
  if (n >= 24 && std::memcmp(b, "\x89PNG\r\n\x1a\n", 8) == 0 &&
      std::memcmp(b + 12, "IHDR", 4) == 0) {
    *w = be32(16);
    *h = be32(20);
    return true;
  }
  if (n < 3 || b[0] != 'P' || b[1] < '1' || b[1] > '6') return false;
  std::uint64_t v[2] = {0, 0};
  int found = 0;
  for (std::size_t i = 2; i < n && found < 2;) {
    const unsigned char c = static_cast<unsigned char>(b[i]);
    if (c == '#') {
      while (i < n && b[i] != '\n') ++i;
    } else if (std::isspace(c)) {
      ++i;
    } else if (std::isdigit(c)) {
      std::uint64_t x = 0;
      for (; i < n && std::isdigit(static_cast<unsigned char>(b[i])); ++i) {
        x = std::min<std::uint64_t>(x * 10 + (b[i] - '0'), std::uint64_t{1} << 32);
      }
      v[found++] = x;
    } else {
      return false;
    }
  }
  if (found < 2) return false;
  *w = v[0];
  *h = v[1];
  return true;
}

std::string directoryOf(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

}  // namespace

MapServerYaml readMapServerYaml(const std::string& file) {
  YAML::Node doc;
  try {
    doc = YAML::LoadFile(file);
  } catch (const YAML::BadFile&) {
    fail(file, "cannot open the file");
  } catch (const YAML::ParserException& e) {
    fail(file, "YAML syntax error: " + e.msg, e.mark.line);
  }
  if (!doc.IsMap()) fail(file, "not a YAML mapping");
  MapServerYaml y;

  const YAML::Node image = doc["image"];
  if (!image) fail(file, "missing 'image'");
  if (!image.IsScalar() || image.as<std::string>().empty()) {
    fail(file, "'image' must be a non-empty file name", image.Mark().line);
  }
  y.image = image.as<std::string>();
  if (y.image[0] != '/') y.image = directoryOf(file) + y.image;  // relative to the YAML

  y.resolution = number(doc, "resolution", file);
  if (!(y.resolution > 0.0)) {
    std::ostringstream m;
    m << "resolution " << y.resolution << " is not positive";
    fail(file, m.str(), doc["resolution"].Mark().line);
  }

  const YAML::Node origin = doc["origin"];
  if (!origin) fail(file, "missing 'origin'");
  if (!origin.IsSequence() || origin.size() != 3) {
    fail(file, "'origin' must be [x, y, yaw]", origin.Mark().line);
  }
  for (int i = 0; i < 3; ++i) {
    try {
      y.origin[i] = origin[i].as<double>();
    } catch (const YAML::Exception&) {
      fail(file, "'origin' must be [x, y, yaw] numbers", origin.Mark().line);
    }
    if (!std::isfinite(y.origin[i])) fail(file, "'origin' is not finite", origin.Mark().line);
  }

  const YAML::Node negate = doc["negate"];
  if (!negate) fail(file, "missing 'negate'");
  try {
    y.negate = negate.as<int>() != 0;  // map_server reads an int
  } catch (const YAML::Exception&) {
    try {
      y.negate = negate.as<bool>();
    } catch (const YAML::Exception&) {
      fail(file, "'negate' must be 0 or 1", negate.Mark().line);
    }
  }

  y.occupied_thresh = number(doc, "occupied_thresh", file);
  y.free_thresh = number(doc, "free_thresh", file);
  if (!(0.0 <= y.free_thresh && y.free_thresh < y.occupied_thresh && y.occupied_thresh <= 1.0)) {
    std::ostringstream m;
    m << "thresholds must satisfy 0 <= free_thresh < occupied_thresh <= 1 (free_thresh "
      << y.free_thresh << ", occupied_thresh " << y.occupied_thresh << ")";
    fail(file, m.str(), doc["free_thresh"].Mark().line);
  }

  if (const YAML::Node mode = doc["mode"]) {
    const std::string s = mode.IsScalar() ? mode.as<std::string>() : std::string();
    if (s == "trinary") {
      y.mode = MapServerMode::kTrinary;
    } else if (s == "scale") {
      y.mode = MapServerMode::kScale;
    } else if (s == "raw") {
      y.mode = MapServerMode::kRaw;
    } else {
      fail(file, "mode '" + s + "' is not trinary, scale or raw", mode.Mark().line);
    }
  }
  return y;
}

std::vector<std::int8_t> mapServerOccupancy(const MapServerYaml& y, int* width, int* height) {
  auto too_big = [&](std::uint64_t w, std::uint64_t h) {
    std::ostringstream m;
    m << "the image is " << w << " x " << h << " pixels, more than the " << kMaxCells
      << " cells a map may have";
    fail(y.image, m.str());
  };
  std::uint64_t header_w = 0, header_h = 0;
  if (headerSize(y.image, &header_w, &header_h) && header_w * header_h > kMaxCells)
    too_big(header_w, header_h);
  cv::Mat img;
  try {
    img = readImageFile(y.image, ImageReadMode::kAsIs);  // loads the codecs module on first use
  } catch (const std::bad_alloc&) {
    fail(y.image, "not enough memory to decode the image");
  } catch (const std::runtime_error& e) {  // OpenCV's own size limit, or no codecs module
    fail(y.image, std::string("cannot read the image: ") + e.what());
  }
  if (img.empty()) fail(y.image, "cannot read the image (missing file or unsupported format)");
  if (static_cast<std::uint64_t>(img.cols) * static_cast<std::uint64_t>(img.rows) > kMaxCells) {
    too_big(static_cast<std::uint64_t>(img.cols), static_cast<std::uint64_t>(img.rows));
  }
  if (img.depth() == CV_16U) img.convertTo(img, CV_8U, 1.0 / 257.0);
  if (img.depth() != CV_8U) fail(y.image, "unsupported pixel depth (need 8 or 16 bits)");
  const int channels = img.channels();
  if (channels != 1 && channels != 2 && channels != 3 && channels != 4) {
    fail(y.image, "unsupported channel count");
  }
  const bool has_alpha = channels == 2 || channels == 4;
  // map_server: trinary mode averages alpha in with the colours; other modes leave it out.
  const int avg_channels =
      (y.mode == MapServerMode::kTrinary || !has_alpha) ? channels : channels - 1;
  const int w = img.cols, h = img.rows;
  std::vector<std::int8_t> data(static_cast<std::size_t>(w) * h);
  for (int j = 0; j < h; ++j) {
    const std::uint8_t* row = img.ptr<std::uint8_t>(j);
    for (int i = 0; i < w; ++i) {
      const std::uint8_t* p = row + static_cast<std::size_t>(i) * channels;
      int sum = 0;
      for (int k = 0; k < avg_channels; ++k) sum += p[k];
      double avg = sum / static_cast<double>(avg_channels);
      const int alpha = has_alpha ? p[channels - 1] : 1;
      if (y.negate) avg = 255.0 - avg;
      unsigned char value;
      if (y.mode == MapServerMode::kRaw) {
        value = static_cast<unsigned char>(avg);
      } else {
        const double occ = (255.0 - avg) / 255.0;
        if (occ > y.occupied_thresh) {
          value = 100;
        } else if (occ < y.free_thresh) {
          value = 0;
        } else if (y.mode == MapServerMode::kTrinary || alpha < 1) {
          value = static_cast<unsigned char>(-1);
        } else {
          const double ratio = (occ - y.free_thresh) / (y.occupied_thresh - y.free_thresh);
          value = static_cast<unsigned char>(1 + 98 * ratio);
        }
      }
      // Image row j is map row h - 1 - j: cell (0, 0) is the bottom-left pixel.
      data[static_cast<std::size_t>(h - 1 - j) * w + i] = static_cast<std::int8_t>(value);
    }
  }
  *width = w;
  *height = h;
  return data;
}

GridMap loadMapServerMap(const std::string& yaml_path, const OccupancyConversion& conversion) {
  const MapServerYaml y = readMapServerYaml(yaml_path);
  int w = 0, h = 0;
  std::vector<std::int8_t> occ = mapServerOccupancy(y, &w, &h);
  if (y.mode == MapServerMode::kRaw) {
    // Raw values are published as bytes: 0..100 are occupancy, 255 (-1) unknown; 101..254
    // have no occupancy meaning and are treated as obstacles.
    for (auto& v : occ) {
      const int u = static_cast<std::uint8_t>(v);
      if (u > 100 && u < 255) v = 100;
    }
  }
  try {
    return gridMapFromOccupancy(w, h, y.resolution, y.origin[0], y.origin[1], y.origin[2],
                                occ.data(), occ.size(), conversion);
  } catch (const LatticeError& e) {
    fail(yaml_path, e.what());
  }
}

}  // namespace lattice
}  // namespace amha
