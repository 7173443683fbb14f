// Map readers: known cell values at known coordinates for every format, negate, unknown cells,
// modes, and clear errors for malformed input.
#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "amha_planner/lattice/map_loaders.h"
#include "test_support.h"

namespace amha {
namespace lattice {
namespace {

void writeFile(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
}

std::string yaml(const std::string& image, const std::string& extra = "",
                 const std::string& negate = "0") {
  return "image: " + image + "\nresolution: 0.05\norigin: [1.5, -2.0, 0.25]\nnegate: " + negate +
         "\noccupied_thresh: 0.65\nfree_thresh: 0.196\n" + extra;
}

std::string expectMapError(const std::function<void()>& f) {
  try {
    f();
  } catch (const LatticeError& e) {
    EXPECT_EQ(e.kind(), LatticeError::Kind::kMap);
    return e.what();
  }
  ADD_FAILURE() << "no LatticeError";
  return "";
}

// A 4 x 3 image: row 0 (top) = black, 205 (unknown grey), white, 100; row 1 = 254 x4; row 2 = 0,
// 254, 254, 128.
cv::Mat testImage() {
  cv::Mat img(3, 4, CV_8U);
  const std::uint8_t v[3][4] = {{0, 205, 255, 100}, {254, 254, 254, 254}, {0, 254, 254, 128}};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) img.at<std::uint8_t>(r, c) = v[r][c];
  return img;
}

TEST(MapServerTest, TrinaryFlipsRowsAndMarksUnknown) {
  const std::string dir = test::tempDir();
  ASSERT_TRUE(cv::imwrite(dir + "/m.pgm", testImage()));
  writeFile(dir + "/m.yaml", yaml("m.pgm"));  // image relative to the YAML
  const GridMap m = loadMapServerMap(dir + "/m.yaml");
  EXPECT_EQ(m.width, 4);
  EXPECT_EQ(m.height, 3);
  EXPECT_DOUBLE_EQ(m.resolution, 0.05);
  EXPECT_DOUBLE_EQ(m.origin_x, 1.5);
  EXPECT_DOUBLE_EQ(m.origin_y, -2.0);
  EXPECT_DOUBLE_EQ(m.origin_yaw, 0.25);
  // Image row 0 is the top: map row 2.
  EXPECT_EQ(m.at(0, 2), kLethalCost);   // black: occ 1.0
  EXPECT_EQ(m.at(1, 2), kUnknownCost);  // 205: occ 0.196.. between the thresholds
  EXPECT_EQ(m.at(2, 2), kFreeCost);     // white
  EXPECT_EQ(m.at(3, 2), kUnknownCost);  // 100: occ 0.61 -> unknown in trinary mode
  EXPECT_EQ(m.at(0, 1), kFreeCost);
  EXPECT_EQ(m.at(0, 0), kLethalCost);   // image bottom-left is cell (0, 0)
  EXPECT_EQ(m.at(3, 0), kUnknownCost);  // 128: occ 0.498

  OccupancyConversion free_unknown;
  free_unknown.unknown_is_free = true;
  const GridMap f = loadMapServerMap(dir + "/m.yaml", free_unknown);
  EXPECT_EQ(f.at(1, 2), kFreeCost);
  EXPECT_EQ(f.at(0, 2), kLethalCost);
}

TEST(MapServerTest, NegateScaleAndRaw) {
  const std::string dir = test::tempDir();
  ASSERT_TRUE(cv::imwrite(dir + "/m.png", testImage()));
  writeFile(dir + "/neg.yaml", yaml(dir + "/m.png", "", "1"));  // absolute image path
  const GridMap n = loadMapServerMap(dir + "/neg.yaml");
  EXPECT_EQ(n.at(0, 2), kFreeCost);    // black is free when negated
  EXPECT_EQ(n.at(2, 2), kLethalCost);  // white is occupied
  EXPECT_EQ(n.at(0, 1), kLethalCost);  // 254 -> 1 after negation: occ 0.996

  // Scale: 100 -> occ 0.608, ratio (0.608 - 0.196) / (0.65 - 0.196) = 0.907 -> 1 + 98 * 0.907 = 89.
  writeFile(dir + "/scale.yaml", yaml("m.png", "mode: scale\n"));
  int w = 0, h = 0;
  const auto occ = mapServerOccupancy(readMapServerYaml(dir + "/scale.yaml"), &w, &h);
  EXPECT_EQ(occ[2 * 4 + 3], 89);
  EXPECT_EQ(occ[0 * 4 + 3],
            1 + static_cast<int>(98 * ((255 - 128) / 255.0 - 0.196) / (0.65 - 0.196)));
  OccupancyConversion lethal100;
  lethal100.lethal_threshold = 100;
  const GridMap s = loadMapServerMap(dir + "/scale.yaml", lethal100);
  EXPECT_EQ(s.at(3, 2), occupancyToCost(89, lethal100));
  EXPECT_EQ(s.at(3, 2), 1 + std::lround(88 * 251.0 / 97.0));
  EXPECT_EQ(s.at(0, 2), kLethalCost);

  // Raw: the grey value itself; 100 stays 100 (lethal), 128 > 100 counts as an obstacle.
  writeFile(dir + "/raw.yaml", yaml("m.png", "mode: raw\n"));
  const auto raw = mapServerOccupancy(readMapServerYaml(dir + "/raw.yaml"), &w, &h);
  EXPECT_EQ(raw[2 * 4 + 3], 100);
  EXPECT_EQ(raw[2 * 4 + 2], -1);  // 255 reads as -1 (unknown), as map_server publishes it
  EXPECT_EQ(raw[1 * 4 + 0], static_cast<std::int8_t>(254));
  const GridMap r = loadMapServerMap(dir + "/raw.yaml");
  EXPECT_EQ(r.at(2, 2), kUnknownCost);
  EXPECT_EQ(r.at(0, 2), kFreeCost);    // raw 0
  EXPECT_EQ(r.at(0, 1), kLethalCost);  // raw 254
}

TEST(MapServerTest, AlphaIsAveragedInTrinaryMode) {
  const std::string dir = test::tempDir();
  cv::Mat img(1, 2, CV_8UC4);
  img.at<cv::Vec4b>(0, 0) = {255, 255, 255,
                             0};  // white, transparent: mean 191 -> occ 0.25 -> unknown
  img.at<cv::Vec4b>(0, 1) = {255, 255, 255, 255};  // white, opaque -> free
  ASSERT_TRUE(cv::imwrite(dir + "/a.png", img));
  writeFile(dir + "/a.yaml", yaml("a.png"));
  const GridMap m = loadMapServerMap(dir + "/a.yaml");
  EXPECT_EQ(m.at(0, 0), kUnknownCost);
  EXPECT_EQ(m.at(1, 0), kFreeCost);
  // Scale mode ignores alpha in the mean, but a transparent in-between pixel is unknown.
  writeFile(dir + "/b.yaml", yaml("a.png", "mode: scale\n"));
  const GridMap s = loadMapServerMap(dir + "/b.yaml");
  EXPECT_EQ(s.at(0, 0), kFreeCost);
}

TEST(MapServerTest, WillowGarage) {
  AMHA_REQUIRE_SHARED_DATA(data);
  const GridMap m = loadMapServerMap(data + "/maps/ros/willow_garage/willow-2010-02-18-0.10.yaml");
  EXPECT_EQ(m.width, 566);
  EXPECT_EQ(m.height, 608);
  EXPECT_DOUBLE_EQ(m.resolution, 0.1);
  std::size_t unknown = 0, free = 0;
  for (auto c : m.cost) {
    unknown += c == kUnknownCost;
    free += c == kFreeCost;
  }
  EXPECT_GE(unknown, 224526u);  // the grey 205 pixels (and darker greys)
  EXPECT_GT(free, 88758u);      // 254 pixels and the light greys
}

TEST(MapServerTest, Errors) {
  const std::string dir = test::tempDir();
  ASSERT_TRUE(cv::imwrite(dir + "/m.pgm", testImage()));
  EXPECT_NE(expectMapError([&] { loadMapServerMap(dir + "/missing.yaml"); }).find("cannot open"),
            std::string::npos);
  writeFile(dir + "/a.yaml", yaml("nothere.pgm"));
  EXPECT_NE(
      expectMapError([&] { loadMapServerMap(dir + "/a.yaml"); }).find("nothere.pgm: cannot read"),
      std::string::npos);
  writeFile(dir + "/b.yaml", yaml("m.pgm", "mode: fancy\n"));
  EXPECT_NE(
      expectMapError([&] { loadMapServerMap(dir + "/b.yaml"); }).find("b.yaml:7: mode 'fancy'"),
      std::string::npos);
  writeFile(dir + "/c.yaml",
            "image: m.pgm\nresolution: -1\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: "
            "0.65\nfree_thresh: 0.2\n");
  EXPECT_NE(expectMapError([&] {
              loadMapServerMap(dir + "/c.yaml");
            }).find("c.yaml:2: resolution -1 is not positive"),
            std::string::npos);
  writeFile(dir + "/d.yaml",
            "image: m.pgm\nresolution: 0.1\norigin: [0, 0]\nnegate: 0\noccupied_thresh: "
            "0.65\nfree_thresh: 0.2\n");
  EXPECT_NE(expectMapError([&] {
              loadMapServerMap(dir + "/d.yaml");
            }).find("'origin' must be [x, y, yaw]"),
            std::string::npos);
  writeFile(dir + "/e.yaml",
            "image: m.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\n");
  EXPECT_NE(
      expectMapError([&] { loadMapServerMap(dir + "/e.yaml"); }).find("missing 'free_thresh'"),
      std::string::npos);
  writeFile(dir + "/f.yaml", "image: [m.pgm\n");
  EXPECT_NE(expectMapError([&] { loadMapServerMap(dir + "/f.yaml"); }).find("YAML syntax error"),
            std::string::npos);
}

TEST(MovingAiTest, CellsUpscaleAndFlip) {
  const std::string dir = test::tempDir();
  writeFile(dir + "/t.map", "type octile\nheight 2\nwidth 3\nmap\n@.T\n.GS\n");
  const GridMap m = loadMovingAiMap(dir + "/t.map", 0.2);
  EXPECT_EQ(m.width, 3);
  EXPECT_EQ(m.height, 2);
  EXPECT_DOUBLE_EQ(m.resolution, 0.2);
  EXPECT_EQ(m.at(0, 1), kLethalCost);  // the file's top row is the map's top
  EXPECT_EQ(m.at(1, 1), kFreeCost);
  EXPECT_EQ(m.at(2, 1), kLethalCost);
  EXPECT_EQ(m.at(0, 0), kFreeCost);
  EXPECT_EQ(m.at(2, 0), kFreeCost);
  const GridMap u = loadMovingAiMap(dir + "/t.map", 0.05, 4);
  EXPECT_EQ(u.width, 12);
  EXPECT_EQ(u.height, 8);
  for (int y = 4; y < 8; ++y) {
    for (int x = 0; x < 4; ++x) EXPECT_EQ(u.at(x, y), kLethalCost);
    for (int x = 4; x < 8; ++x) EXPECT_EQ(u.at(x, y), kFreeCost);
  }
  writeFile(dir + "/bad.map", "type octile\nheight 2\nwidth 3\nmap\n@.T\n.X.\n");
  EXPECT_NE(expectMapError([&] {
              loadMovingAiMap(dir + "/bad.map", 0.1);
            }).find("bad.map:6: unknown terrain character 'X' in column 2"),
            std::string::npos);
  writeFile(dir + "/short.map", "type octile\nheight 3\nwidth 3\nmap\n@.T\n...\n");
  EXPECT_NE(expectMapError([&] {
              loadMovingAiMap(dir + "/short.map", 0.1);
            }).find("missing map row 3 of 3"),
            std::string::npos);
  writeFile(dir + "/wide.map", "type octile\nheight 1\nwidth 3\nmap\n@...\n");
  EXPECT_NE(expectMapError([&] {
              loadMovingAiMap(dir + "/wide.map", 0.1);
            }).find("wide.map:5: row has 4 characters, width is 3"),
            std::string::npos);
  EXPECT_NE(expectMapError([&] {
              loadMovingAiMap(dir + "/t.map", 0.0);
            }).find("resolution must be positive"),
            std::string::npos);
}

TEST(MovingAiTest, SharedMaps) {
  AMHA_REQUIRE_SHARED_DATA(data);
  const GridMap m = loadMovingAiMap(data + "/maps/movingai/maze-32-32-4.map", 0.1, 2);
  EXPECT_EQ(m.width, 64);
  EXPECT_EQ(m.height, 64);
  // The first map row in the file is the top map row: compare with the text.
  std::ifstream in(data + "/maps/movingai/maze-32-32-4.map");
  std::string line;
  for (int i = 0; i < 5; ++i) std::getline(in, line);
  for (int c = 0; c < 32; ++c) {
    const bool blocked = line[c] == '@' || line[c] == 'T' || line[c] == 'O' || line[c] == 'W';
    EXPECT_EQ(m.at(2 * c + 1, 63), blocked ? kLethalCost : kFreeCost) << c;
  }
}

TEST(SbplEnvironmentTest, Env1) {
  AMHA_REQUIRE_SHARED_DATA(data);
  const SbplEnvironment e = loadSbplEnvironment(data + "/sbpl/env1.cfg");
  EXPECT_EQ(e.map.width, 15);
  EXPECT_EQ(e.map.height, 15);
  EXPECT_DOUBLE_EQ(e.map.resolution, 0.025);
  EXPECT_EQ(e.obsthresh, 1);
  EXPECT_EQ(e.cost_inscribed_thresh, 1);
  EXPECT_EQ(e.num_theta_dirs, 16);
  EXPECT_DOUBLE_EQ(e.nominal_speed, 1.0);
  EXPECT_DOUBLE_EQ(e.time_to_turn_45, 2.0);
  EXPECT_DOUBLE_EQ(e.start.x, 0.11);
  EXPECT_DOUBLE_EQ(e.goal.y, 0.3);
  // Row 0 of the file is y = 0: "0 0 0 0 0 0 1 1 0 ..." -> cells (6, 0), (7, 0) are obstacles.
  EXPECT_EQ(e.map.at(5, 0), kFreeCost);
  EXPECT_EQ(e.map.at(6, 0), kLethalCost);
  EXPECT_EQ(e.map.at(7, 0), kLethalCost);
  EXPECT_EQ(e.map.at(0, 7), kLethalCost);  // row 7: "1 1 1 1 0 ..."
  EXPECT_EQ(e.map.at(11, 14), kLethalCost);
  EXPECT_EQ(e.map.at(10, 14), kFreeCost);
}

TEST(SbplEnvironmentTest, CubicleCostsMatchTheText) {
  AMHA_REQUIRE_SHARED_DATA(data);
  const std::string path = data + "/sbpl/cubicle-25mm-inflated-env.cfg";
  const SbplEnvironment e = loadSbplEnvironment(path);
  ASSERT_EQ(e.map.width, 436);
  ASSERT_EQ(e.map.height, 473);
  EXPECT_EQ(e.obsthresh, 254);
  EXPECT_EQ(e.cost_inscribed_thresh, 253);
  EXPECT_EQ(e.cost_possibly_circumscribed_thresh, 128);
  EXPECT_DOUBLE_EQ(e.time_to_turn_45, 20.0);
  // Independent reading of the numbers after "environment:".
  std::ifstream in(path);
  std::string tok;
  while (in >> tok && tok != "environment:") {
  }
  std::vector<int> raw;
  int v;
  while (in >> v) raw.push_back(v);
  ASSERT_EQ(raw.size(), 436u * 473u);
  int distinct_nonzero = 0;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    ASSERT_EQ(e.map.cost[i], raw[i]) << i;  // thresholds 254/253: costs unchanged
    distinct_nonzero += raw[i] != 0 && raw[i] < 253;
  }
  EXPECT_GT(distinct_nonzero, 1000);
}

TEST(SbplEnvironmentTest, Errors) {
  const std::string dir = test::tempDir();
  const std::string head =
      "discretization(cells): 2 2\nobsthresh: 254\ncost_inscribed_thresh: "
      "253\ncost_possibly_circumscribed_thresh: 128\n"
      "cellsize(meters): 0.1\nnominalvel(mpersecs): 1.0\ntimetoturn45degsinplace(secs): 1.0\n"
      "start(meters,rads): 0.05 0.05 0\nend(meters,rads): 0.15 0.15 0\nenvironment:\n";
  writeFile(dir + "/ok.cfg", head + "0 1\n253 254\n");
  const SbplEnvironment ok = loadSbplEnvironment(dir + "/ok.cfg");
  EXPECT_EQ(ok.map.at(1, 0), 1);
  EXPECT_EQ(ok.map.at(0, 1), kInscribedCost);
  EXPECT_EQ(ok.map.at(1, 1), kLethalCost);
  writeFile(dir + "/short.cfg", head + "0 1\n253\n");
  EXPECT_NE(expectMapError([&] {
              loadSbplEnvironment(dir + "/short.cfg");
            }).find("the environment ends at cell (1, 1)"),
            std::string::npos);
  writeFile(dir + "/badcost.cfg", head + "0 1\n253 300\n");
  EXPECT_NE(expectMapError([&] {
              loadSbplEnvironment(dir + "/badcost.cfg");
            }).find("badcost.cfg:12: cell (1, 1): cost '300'"),
            std::string::npos);
  writeFile(dir + "/label.cfg", "discretization(cells): 2 2\nobsthresh 254\n");
  EXPECT_NE(expectMapError([&] {
              loadSbplEnvironment(dir + "/label.cfg");
            }).find("label.cfg:2: expected 'obsthresh:' but found 'obsthresh'"),
            std::string::npos);
  writeFile(dir + "/extra.cfg", head + "0 1\n253 254 7\n");
  EXPECT_NE(expectMapError([&] { loadSbplEnvironment(dir + "/extra.cfg"); }).find("unexpected '7'"),
            std::string::npos);
}

TEST(OccupancyTest, ConversionAndValidation) {
  OccupancyConversion c;
  EXPECT_EQ(occupancyToCost(-1, c), kUnknownCost);
  EXPECT_EQ(occupancyToCost(0, c), kFreeCost);
  EXPECT_EQ(occupancyToCost(64, c), 1 + std::lround(63 * 251.0 / 97.0));
  EXPECT_EQ(occupancyToCost(65, c), kLethalCost);
  EXPECT_EQ(occupancyToCost(100, c), kLethalCost);
  OccupancyConversion costmap;  // the translation costmap_2d publishes, read back
  costmap.lethal_threshold = 100;
  EXPECT_EQ(occupancyToCost(99, costmap), kInscribedCost);
  EXPECT_EQ(occupancyToCost(98, costmap), 252);
  EXPECT_EQ(occupancyToCost(1, costmap), 1);
  for (int cost = 1; cost <= 252; ++cost) {
    const int published = 1 + (97 * (cost - 1)) / 251;  // costmap_2d's cost_translation_table
    const int back = occupancyToCost(published, costmap);
    EXPECT_LE(std::abs(back - cost), 3) << cost;
  }
  costmap.unknown_is_free = true;
  EXPECT_EQ(occupancyToCost(-1, costmap), kFreeCost);

  const std::int8_t data[6] = {0, 100, -1, 50, 99, 10};
  const GridMap m = gridMapFromOccupancy(3, 2, 0.05, 1, 2, 0.5, data, 6, c);
  EXPECT_EQ(m.at(0, 0), kFreeCost);
  EXPECT_EQ(m.at(1, 0), kLethalCost);
  EXPECT_EQ(m.at(2, 0), kUnknownCost);
  EXPECT_EQ(m.at(2, 1), occupancyToCost(10, c));
  auto err = [&](const std::function<void()>& f) { return expectMapError(f); };
  EXPECT_NE(
      err([&] { gridMapFromOccupancy(3, 2, 0.05, 0, 0, 0, data, 5, c); }).find("data has 5 values"),
      std::string::npos);
  EXPECT_NE(
      err([&] { gridMapFromOccupancy(0, 2, 0.05, 0, 0, 0, data, 0, c); }).find("not positive"),
      std::string::npos);
  EXPECT_NE(err([&] { gridMapFromOccupancy(3, 2, NAN, 0, 0, 0, data, 6, c); }).find("resolution"),
            std::string::npos);
  EXPECT_NE(err([&] {
              gridMapFromOccupancy(3, 2, 0.05, NAN, 0, 0, data, 6, c);
            }).find("origin is not finite"),
            std::string::npos);
  EXPECT_NE(err([&] {
              gridMapFromOccupancy(3, 2, 0.05, 0, 0, 0, data, 6, c, 5);
            }).find("exceeds the limit"),
            std::string::npos);
}

}  // namespace
}  // namespace lattice
}  // namespace amha
