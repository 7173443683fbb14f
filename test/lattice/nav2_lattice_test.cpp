// Nav2 lattice files: our fixture and (when present) Nav2's sample files load with the right
// counts; corrupted files are refused with errors that name the field and the value; generated
// sets written as .json and .mprim read back the same; backward twins of a Nav2 set.
#include <sys/stat.h>
#include <cmath>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "amha_planner/lattice/lattice_graph.h"
#include "amha_planner/lattice/motion_primitives.h"
#include "test_support.h"

namespace amha {
namespace lattice {
namespace {

const std::string kFixture =
    "test/lattice/data/nav2_diff_8_headings.json";  // tests run from the source tree
const std::string kSamples =
    "/work/smac-bench/src/nav2_smac_planner/lattice_primitives/sample_primitives";

bool exists(const std::string& path) {
  struct stat st;
  return stat(path.c_str(), &st) == 0;
}

nlohmann::json fixture() {
  std::ifstream in(kFixture);
  return nlohmann::json::parse(in);
}

// The error readNav2Lattice gives for `doc` (a failure if it gives none).
std::string errorFor(const std::string& text, double map_resolution = 0.0) {
  std::istringstream in(text);
  try {
    readNav2Lattice(in, "t.json", map_resolution);
  } catch (const LatticeError& e) {
    EXPECT_EQ(e.kind(), LatticeError::Kind::kPrimitives);
    return e.what();
  }
  ADD_FAILURE() << "no error for a corrupted file";
  return "";
}
std::string errorFor(const nlohmann::json& doc, double map_resolution = 0.0) {
  return errorFor(doc.dump(), map_resolution);
}

TEST(Nav2Lattice, FixtureLoads) {
  const PrimitiveSet s = readNav2LatticeFile(kFixture, 0.1);
  EXPECT_EQ(s.num_headings, 8);
  EXPECT_EQ(s.primitives.size(), 44u);
  EXPECT_EQ(s.motion_model, "diff");
  EXPECT_DOUBLE_EQ(s.min_turning_radius, 0.3);
  EXPECT_FALSE(s.uniform);
  for (int h = 0; h < 8; ++h) {
    const auto r = s.range(h);
    EXPECT_EQ(r.second - r.first, h % 2 == 0 ? 6u : 5u) << "heading " << h;
    for (std::size_t i = r.first; i < r.second; ++i) {
      const MotionPrimitive& p = s.primitives[i];
      // The start pose, which Nav2 leaves out of moves, comes first.
      EXPECT_EQ(p.poses.front().x, 0.0);
      EXPECT_EQ(p.poses.front().y, 0.0);
      EXPECT_NEAR(angleDistance(p.poses.front().theta, s.heading_angles[h]), 0.0, 1e-9);
      EXPECT_NEAR(p.poses.back().x, p.end_dx * 0.1, 1e-9);
    }
  }
  // Heading 0's left arc: (0.3, 0.1) at heading 1, radius 0.34142.
  const auto r0 = s.range(0);
  bool found = false;
  for (std::size_t i = r0.first; i < r0.second; ++i) {
    const MotionPrimitive& p = s.primitives[i];
    if (p.end_heading == 1 && (p.end_dx != 0 || p.end_dy != 0)) {
      found = true;
      EXPECT_EQ(p.end_dx, 3);
      EXPECT_EQ(p.end_dy, 1);
      EXPECT_NEAR(p.turning_radius, 0.34142, 1e-5);
      EXPECT_NEAR(p.arc_length + p.straight_length, 0.32673, 1e-5);
    }
  }
  EXPECT_TRUE(found);
}

TEST(Nav2Lattice, NavSampleFilesLoadWithTheirCounts) {
  if (!exists(kSamples)) GTEST_SKIP() << "Nav2's sample files are not on this machine";
  struct Sample {
    const char* file;
    std::size_t prims;
    const char* model;
  } samples[] = {{"5cm_resolution/0.5m_turning_radius/ackermann/output.json", 72, "ackermann"},
                 {"5cm_resolution/0.5m_turning_radius/diff/output.json", 104, "diff"},
                 {"5cm_resolution/0.5m_turning_radius/omni/output.json", 136, "omni"},
                 {"5cm_resolution/1m_turning_radius/ackermann/output.json", 56, "ackermann"}};
  for (const Sample& f : samples) {
    const PrimitiveSet s = readNav2LatticeFile(kSamples + "/" + f.file, 0.05);
    EXPECT_EQ(s.primitives.size(), f.prims) << f.file;
    EXPECT_EQ(s.num_headings, 16) << f.file;
    EXPECT_EQ(s.motion_model, f.model) << f.file;
  }
  const PrimitiveSet ack = readNav2LatticeFile(kSamples + "/" + samples[0].file);
  for (int h = 0; h < 16; ++h) {
    const auto r = ack.range(h);
    EXPECT_EQ(r.second - r.first, h % 2 == 0 ? 5u : 4u) << "heading " << h;
  }
  // Nav2's own test file uses end_angle_index 15 with num_of_headings 15.
  try {
    readNav2LatticeFile(kSamples + "/test/output.json");
    ADD_FAILURE();
  } catch (const LatticeError& e) {
    EXPECT_NE(std::string(e.what()).find("'end_angle_index' 15 is not an integer in 0..14"),
              std::string::npos)
        << e.what();
  }
}

TEST(Nav2Lattice, CorruptedFilesGiveNamedErrors) {
  const nlohmann::json good = fixture();
  auto changed = [&](const std::function<void(nlohmann::json&)>& change) {
    nlohmann::json d = good;
    change(d);
    return d;
  };
  auto expectError = [](const std::string& error, const std::string& part) {
    EXPECT_NE(error.find(part), std::string::npos) << "error: " << error << "\nexpected: " << part;
  };
  expectError(
      errorFor(good, 0.05),
      "t.json: lattice_metadata: 'grid_resolution' 0.1 does not match the map's resolution 0.05");
  expectError(errorFor(std::string("{\"lattice_metadata\": {,}")),
              "t.json: not valid JSON: parse error at line 1, column 23");
  expectError(errorFor(std::string("[1, 2]")),
              "t.json: the document: must be a JSON object, not [1,2]");
  // A number no double holds (found by the fuzzer: the JSON library throws out_of_range).
  expectError(errorFor(std::string("{\"lattice_metadata\": {\"turning_radius\": 2.35e2345}}")),
              "t.json: not valid JSON: number overflow parsing '2.35e2345'");
  expectError(errorFor(changed([](auto& d) { d.erase("primitives"); })),
              "t.json: the document: missing 'primitives'");
  expectError(errorFor(changed([](auto& d) { d["lattice_metadata"].erase("heading_angles"); })),
              "lattice_metadata: missing 'heading_angles'");
  expectError(errorFor(changed([](auto& d) { d["lattice_metadata"]["motion_model"] = "car"; })),
              "'motion_model' must be \"ackermann\", \"diff\" or \"omni\", not \"car\"");
  expectError(errorFor(changed([](auto& d) { d["lattice_metadata"]["grid_resolution"] = -1; })),
              "'grid_resolution' -1 is not a resolution in metres");
  expectError(errorFor(changed([](auto& d) { d["lattice_metadata"]["num_of_headings"] = 9; })),
              "'heading_angles' has 8 angles, not num_of_headings = 9");
  expectError(errorFor(changed([](auto& d) { d["lattice_metadata"]["heading_angles"][3] = 0.5; })),
              "'heading_angles'[3] 0.5 is not greater than the angle before it");
  expectError(errorFor(changed([](auto& d) { d["lattice_metadata"]["heading_angles"][7] = 7.0; })),
              "'heading_angles'[7] 7 is not in [0, 2 pi)");
  expectError(
      errorFor(changed([](auto& d) { d["lattice_metadata"]["number_of_trajectories"] = 45; })),
      "'primitives' has 44 primitives, but lattice_metadata's number_of_trajectories says 45");
  expectError(
      errorFor(changed([](auto& d) { d["primitives"][3]["start_angle_index"] = 8; })),
      "t.json: primitives[3] (trajectory_id 3): 'start_angle_index' 8 is not an integer in 0..7");
  expectError(
      errorFor(changed([](auto& d) { d["primitives"][3]["end_angle_index"] = "one"; })),
      "primitives[3] (trajectory_id 3): 'end_angle_index' must be an integer in 0..7, not \"one\"");
  expectError(errorFor(changed([](auto& d) { d["primitives"][5].erase("left_turn"); })),
              "primitives[5] (trajectory_id 5): missing 'left_turn' (true or false)");
  expectError(errorFor(changed([](auto& d) { d["primitives"][5]["arc_length"] = -0.2; })),
              "'arc_length' -0.2 is not a length >= 0 in metres");
  expectError(errorFor(changed([](auto& d) {
                d["primitives"][2]["poses"][1] = {0.1, "y", 0.2};
              })),
              "primitives[2] (trajectory_id 2): 'poses'[1] must be [x, y, yaw] (3 finite numbers), "
              "not [0.1,\"y\",0.2]");
  expectError(
      errorFor(changed([](auto& d) { d["primitives"][2]["poses"] = nlohmann::json::array(); })),
      "'poses' has 0 poses");
  expectError(errorFor(changed([](auto& d) { d["primitives"][2]["poses"].back()[0] = 0.33; })),
              "primitives[2] (trajectory_id 2): the last pose [0.33,0.1,0.7853981633974483] is not "
              "a cell centre at end "
              "heading 1");
  expectError(errorFor(changed([](auto& d) { d["primitives"][2]["end_angle_index"] = 2; })),
              "is not a cell centre at end heading 2");
  expectError(errorFor(changed([](auto& d) { d["primitives"][2]["poses"].back()[0] = 300.0; })),
              "cells long (at most 1000)");
  // Every primitive of heading 5 moved to heading 4: heading 5 has none.
  expectError(errorFor(changed([](auto& d) {
                for (auto& p : d["primitives"]) {
                  if (p["start_angle_index"] == 5) p["start_angle_index"] = 4;
                }
              })),
              "heading 5 has no primitives");
  try {
    readNav2LatticeFile("/nonexistent/x.json");
    ADD_FAILURE();
  } catch (const LatticeError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/x.json: cannot open the file"),
              std::string::npos);
  }
}

// .mprim files round poses to 6 decimals and do not keep arc and straight lengths (the reader
// estimates them from the poses): length_tolerance says how closely they must agree.
void expectSameMotions(const PrimitiveSet& a, const PrimitiveSet& b, double pose_tolerance,
                       double length_tolerance = 1e-5) {
  ASSERT_EQ(a.num_headings, b.num_headings);
  ASSERT_EQ(a.primitives.size(), b.primitives.size());
  for (int h = 0; h < a.num_headings; ++h)
    EXPECT_NEAR(a.heading_angles[h], b.heading_angles[h], 1e-9);
  for (std::size_t i = 0; i < a.primitives.size(); ++i) {
    const MotionPrimitive &p = a.primitives[i], &q = b.primitives[i];
    EXPECT_EQ(p.start_heading, q.start_heading);
    EXPECT_EQ(p.end_dx, q.end_dx);
    EXPECT_EQ(p.end_dy, q.end_dy);
    EXPECT_EQ(p.end_heading, q.end_heading);
    EXPECT_EQ(p.reverse, q.reverse);
    EXPECT_NEAR(p.turning_radius, q.turning_radius, 1e-6);
    EXPECT_NEAR(p.arc_length, q.arc_length, length_tolerance);
    EXPECT_NEAR(p.straight_length, q.straight_length, length_tolerance);
    ASSERT_EQ(p.poses.size(), q.poses.size());
    for (std::size_t k = 0; k < p.poses.size(); ++k) {
      EXPECT_NEAR(p.poses[k].x, q.poses[k].x, pose_tolerance);
      EXPECT_NEAR(p.poses[k].y, q.poses[k].y, pose_tolerance);
      EXPECT_NEAR(angleDistance(p.poses[k].theta, q.poses[k].theta), 0.0, pose_tolerance);
    }
  }
}

TEST(Nav2Lattice, GeneratedSetsReadBackFromBothFormats) {
  const std::string dir = test::tempDir();
  for (MotionModel model :
       {MotionModel::kAckermann, MotionModel::kDifferential, MotionModel::kOmni}) {
    PrimitiveGeneratorOptions o;
    o.motion_model = model;
    o.resolution = 0.1;
    const PrimitiveSet s = generatePrimitives(o);
    writePrimitiveFile(dir + "/s.json", s);
    const PrimitiveSet j = readPrimitiveFile(dir + "/s.json", 0.1);
    EXPECT_EQ(j.motion_model, motionModelName(model));
    EXPECT_DOUBLE_EQ(j.min_turning_radius, o.turning_radius);
    expectSameMotions(s, j, 1e-6);
    // .mprim: SBPL's format pads headings to the same count; the reader drops the copies.
    writePrimitiveFile(dir + "/s.mprim", s);
    expectSameMotions(s, readPrimitiveFile(dir + "/s.mprim", 0.1), 1e-6, 1e-3);
  }
  // Backward motions are not written to a Nav2 file (Nav2 makes them itself) ...
  PrimitiveGeneratorOptions o;
  o.allow_reverse = true;
  o.motion_model = MotionModel::kAckermann;
  const PrimitiveSet with = generatePrimitives(o);
  writeNav2LatticeFile(dir + "/r.json", with);
  const PrimitiveSet forward_only = readNav2LatticeFile(dir + "/r.json");
  EXPECT_EQ(forward_only.primitives.size() * 2, with.primitives.size());
  // ... and a planner given the file with allow_reverse adds them back, as Smac does.
  LatticeConfig c;
  c.motion.mprim_file = dir + "/r.json";
  c.motion.allow_reverse = true;
  c.cost.reverse_multiplier = o.reverse_multiplier;
  expectSameMotions(with, primitivesFor(c, 0.05), 1e-6);
}

TEST(Nav2Lattice, PlannerUsesAJsonFileAndChecksItsResolution) {
  auto map = test::randomMap(60, 60, 0.1, 3, 0, 0);
  LatticeConfig c;
  c.motion.mprim_file = kFixture;
  c.robot.radius = 0.1;
  const LatticeGraph g(map, c);
  EXPECT_EQ(g.numHeadings(), 8);
  EXPECT_EQ(g.actions().size(), 44u);
  auto fine = test::randomMap(60, 60, 0.05, 3, 0, 0);
  try {
    LatticeGraph bad(fine, c);
    ADD_FAILURE();
  } catch (const LatticeError& e) {
    EXPECT_EQ(e.kind(), LatticeError::Kind::kPrimitives);
    EXPECT_NE(std::string(e.what()).find("does not match the map's resolution 0.05"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace lattice
}  // namespace amha
