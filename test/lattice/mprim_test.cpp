// .mprim reading (every shared file, uniform and non-uniform), validation errors, the
// generator and writer round trip.
#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>

#include <gtest/gtest.h>

#include "amha_planner/lattice/motion_primitives.h"
#include "test_support.h"

namespace amha {
namespace lattice {
namespace {

std::string expectPrimError(const std::string& text, double res = 0.0) {
  std::istringstream in(text);
  try {
    readMprim(in, "t.mprim", res);
  } catch (const LatticeError& e) {
    EXPECT_EQ(e.kind(), LatticeError::Kind::kPrimitives);
    return e.what();
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return "";
}

// Two headings (uniform, pi apart), one primitive each: a minimal valid file.
const char* kSmall =
    "resolution_m: 0.1\n"
    "numberofangles: 2\n"
    "totalnumberofprimitives: 2\n"
    "primID: 0\nstartangle_c: 0\nendpose_c: 1 0 0\nadditionalactioncostmult: 1\nintermediateposes: "
    "2\n"
    "0 0 0\n0.1 0 0\n"
    "primID: 0\nstartangle_c: 1\nendpose_c: -1 0 1\nadditionalactioncostmult: "
    "2\nintermediateposes: 2\n"
    "0 0 3.14159\n-0.1 0 3.14159\n";

TEST(MprimTest, SharedFilesLoadWithTheirCounts) {
  AMHA_REQUIRE_SHARED_DATA(data);
  struct Case {
    const char* file;
    double res;
    std::size_t prims;
  } cases[] = {{"pr2.mprim", 0.025, 112},
               {"pr2_10cm.mprim", 0.1, 256},
               {"unicycle_noturninplace.mprim", 0.025, 80}};
  for (const Case& c : cases) {
    const PrimitiveSet s = readMprimFile(data + "/sbpl/" + c.file, c.res);
    EXPECT_EQ(s.num_headings, 16) << c.file;
    EXPECT_EQ(s.primitives.size(), c.prims) << c.file;
    EXPECT_TRUE(s.uniform) << c.file;
    for (int h = 0; h < 16; ++h) {
      const auto r = s.range(h);
      EXPECT_EQ(r.second - r.first, c.prims / 16) << c.file << " heading " << h;
      for (std::size_t i = r.first; i < r.second; ++i)
        EXPECT_EQ(s.primitives[i].id, static_cast<int>(i - r.first));
    }
  }
  const PrimitiveSet pr2 = readMprimFile(data + "/sbpl/pr2.mprim");
  const MotionPrimitive& p = pr2.primitives[pr2.range(1).first + 3];  // heading 1, primID 3
  EXPECT_EQ(p.end_dx, 5);
  EXPECT_EQ(p.end_dy, 4);
  EXPECT_EQ(p.end_heading, 2);
  EXPECT_DOUBLE_EQ(p.cost_multiplier, 3.0);
  EXPECT_EQ(p.poses.size(), 10u);
}

TEST(MprimTest, NonUniformFormat) {
  std::ostringstream f;
  f << "resolution_m: 0.1\nmin_turning_radius_m: 0.5\nnumberofangles: 2\nangle:0 0.0\nangle:1 "
       "3.14159265\n"
       "totalnumberofprimitives: 2\n"
       "primID: 0\nstartangle_c: 0\nendpose_c: 2 0 0\nadditionalactioncostmult: 1\nturning_radius: "
       "0.0\nintermediateposes: 3\n"
       "0 0 0\n0.1 0 0\n0.2 0 0\n"
       "primID: 0\nstartangle_c: 1\nendpose_c: 0 0 0\nadditionalactioncostmult: 1\nturning_radius: "
       "-0.7\nintermediateposes: 2\n"
       "0 0 3.14159265\n0 0 0.1\n";
  std::istringstream in(f.str());
  const PrimitiveSet s = readMprim(in, "nu.mprim", 0.1);
  EXPECT_FALSE(s.uniform);
  EXPECT_DOUBLE_EQ(s.min_turning_radius, 0.5);
  EXPECT_EQ(s.primitives[1].end_heading, 0);
  EXPECT_DOUBLE_EQ(s.primitives[1].turning_radius, -0.7);  // SBPL signs it
  EXPECT_EQ(s.headingIndex(0.2), 0);
  EXPECT_EQ(s.headingIndex(2.0), 1);
  EXPECT_EQ(s.headingIndex(-0.3), 0);
}

TEST(MprimTest, ValidationErrorsNameLineAndProblem) {
  std::istringstream ok(kSmall);
  EXPECT_EQ(readMprim(ok, "t.mprim", 0.1).primitives.size(), 2u);
  const std::string s = kSmall;
  auto replace = [&](const std::string& from, const std::string& to) {
    std::string t = s;
    const std::size_t at = t.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return t.replace(at, from.size(), to);
  };
  EXPECT_NE(expectPrimError(kSmall, 0.025).find("t.mprim:1: resolution 0.1 in file != map 0.025"),
            std::string::npos);
  // The end pose must match the last intermediate pose's discretisation.
  EXPECT_NE(expectPrimError(replace("endpose_c: 1 0 0", "endpose_c: 2 0 0"))
                .find("t.mprim:10: primID 0 (start heading 0): last intermediate pose 0.1 0 0 "
                      "discretises to 1 0 0, not endpose_c 2 0 0"),
            std::string::npos);
  EXPECT_NE(expectPrimError(replace("0.1 0 0\n", "0.1 0 3.1\n"))
                .find("discretises to 1 0 1, not endpose_c 1 0 0"),
            std::string::npos);
  EXPECT_NE(expectPrimError(replace("0 0 0\n0.1", "0.2 0 0\n0.1"))
                .find("t.mprim:4: primID 0 (start heading 0): first intermediate pose 0.2 0 0 is "
                      "not in the start cell"),
            std::string::npos);
  EXPECT_NE(expectPrimError(replace("startangle_c: 1", "startangle_c: 2"))
                .find("t.mprim:12: startangle_c 2 is not in 0..1"),
            std::string::npos);
  EXPECT_NE(expectPrimError(replace("additionalactioncostmult: 2", "additionalactioncostmult: 0"))
                .find("t.mprim:14: additionalactioncostmult 0 must be positive"),
            std::string::npos);
  EXPECT_NE(expectPrimError(replace("numberofangles: 2", "numberofangle: 2"))
                .find("t.mprim:2: expected 'numberofangles:' but found 'numberofangle:'"),
            std::string::npos);
  EXPECT_NE(expectPrimError(replace("-0.1 0 3.14159", "-0.1 zero 3.14159"))
                .find("t.mprim:17: expected an intermediate y (a number) but found 'zero'"),
            std::string::npos);
  EXPECT_NE(expectPrimError(replace("totalnumberofprimitives: 2", "totalnumberofprimitives: 3"))
                .find("file ends before primitive 3 of 3"),
            std::string::npos);
  const std::string both_heading_0 =
      "resolution_m: 0.1\nnumberofangles: 2\ntotalnumberofprimitives: 2\n"
      "primID: 0\nstartangle_c: 0\nendpose_c: 1 0 0\nadditionalactioncostmult: "
      "1\nintermediateposes: 2\n0 0 0\n0.1 0 0\n"
      "primID: 1\nstartangle_c: 0\nendpose_c: 2 0 0\nadditionalactioncostmult: "
      "1\nintermediateposes: 2\n0 0 0\n0.2 0 0\n";
  EXPECT_NE(expectPrimError(both_heading_0)
                .find("heading 0 has 2 primitives; every heading needs the same number (2 / 2)"),
            std::string::npos);
  EXPECT_NE(expectPrimError(s + "primID: 7\n")
                .find("t.mprim:18: unexpected 'primID:' after the last primitive"),
            std::string::npos);
  EXPECT_NE(expectPrimError(replace("intermediateposes: 2\n0 0 3", "intermediateposes: 0\n0 0 3"))
                .find("intermediateposes 0 is not in 1..100000"),
            std::string::npos);
  EXPECT_NE(expectPrimError("").find("expected 'resolution_m:' but found the end of the file"),
            std::string::npos);
  try {
    readMprimFile("/nonexistent/x.mprim");
    ADD_FAILURE();
  } catch (const LatticeError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot open"), std::string::npos);
  }
}

void checkGeneratedSet(const PrimitiveSet& s, const PrimitiveGeneratorOptions& o) {
  ASSERT_EQ(s.num_headings, o.num_headings);
  const std::size_t per = s.primitives.size() / s.num_headings;
  std::size_t expected = 4 + (o.allow_reverse ? 3 : 0) + (o.turn_in_place ? 2 : 0);
  EXPECT_EQ(per, expected);
  for (int h = 0; h < s.num_headings; ++h) {
    const auto r = s.range(h);
    ASSERT_EQ(r.second - r.first, per);
    // Headings are the directions of their lattice vectors: straight moves keep the heading.
    const MotionPrimitive& step = s.primitives[r.first];
    EXPECT_NEAR(std::atan2(step.end_dy, step.end_dx), std::remainder(s.heading_angles[h], 2 * M_PI),
                1e-9);
    for (std::size_t i = r.first; i < r.second; ++i) {
      const MotionPrimitive& p = s.primitives[i];
      EXPECT_NEAR(p.poses.front().x, 0.0, 1e-12);
      EXPECT_NEAR(p.poses.front().y, 0.0, 1e-12);
      EXPECT_NEAR(p.poses.back().x, p.end_dx * o.resolution, 1e-12);
      EXPECT_NEAR(p.poses.back().y, p.end_dy * o.resolution, 1e-12);
      EXPECT_NEAR(angleDistance(p.poses.back().theta, s.heading_angles[p.end_heading]), 0.0, 1e-12);
      const int dh = std::abs(p.end_heading - h);
      EXPECT_TRUE(dh == 0 || dh == 1 || dh == s.num_headings - 1);
      if (p.turning_radius != 0.0) {
        EXPECT_GE(std::fabs(p.turning_radius), o.turning_radius - 1e-9);
        // Signed as SBPL does: positive when the heading turns counter-clockwise.
        const double turn =
            std::remainder(s.heading_angles[p.end_heading] - s.heading_angles[h], 2 * M_PI);
        EXPECT_GT(turn * p.turning_radius, 0.0);
        // Consecutive poses continue smoothly: the interpolated path never jumps.
        for (std::size_t k = 1; k < p.poses.size(); ++k) {
          EXPECT_LE(std::hypot(p.poses[k].x - p.poses[k - 1].x, p.poses[k].y - p.poses[k - 1].y),
                    0.5 * o.resolution + 1e-9);
        }
        // Its curvature never exceeds 1 / turning radius: heading change <= distance / R.
        for (std::size_t k = 1; k < p.poses.size(); ++k) {
          const double d =
              std::hypot(p.poses[k].x - p.poses[k - 1].x, p.poses[k].y - p.poses[k - 1].y);
          EXPECT_LE(angleDistance(p.poses[k].theta, p.poses[k - 1].theta),
                    1.01 * d / o.turning_radius + 1e-9);
        }
      } else {
        EXPECT_TRUE(p.end_heading == h ||
                    (p.end_dx == 0 && p.end_dy == 0));  // straight or a turn in place
      }
    }
  }
}

// The legacy generator (PrimitiveGenerator::kLegacy), kept for old benchmarks.
TEST(MprimGeneratorTest, ExactEndsSymmetryAndTurningRadius) {
  for (int headings : {8, 16, 24, 32}) {
    for (bool reverse : {false, true}) {
      PrimitiveGeneratorOptions o;
      o.resolution = 0.05;
      o.num_headings = headings;
      o.turning_radius = 0.4;
      o.allow_reverse = reverse;
      o.turn_in_place = !reverse;
      o.generator = PrimitiveGenerator::kLegacy;
      const PrimitiveSet s = generatePrimitives(o);
      SCOPED_TRACE(headings);
      checkGeneratedSet(s, o);
      EXPECT_EQ(s.uniform, headings == 8);
    }
  }
  PrimitiveGeneratorOptions bad;
  bad.generator = PrimitiveGenerator::kLegacy;
  bad.num_headings = 12;
  EXPECT_THROW(generatePrimitives(bad), LatticeError);
  bad.num_headings = 16;
  bad.turning_radius = 0.0;
  EXPECT_THROW(generatePrimitives(bad), LatticeError);
}

TEST(MprimGeneratorTest, WrittenSetsReadBack) {
  const std::string dir = test::tempDir();
  for (int headings : {8, 16, 32}) {
    PrimitiveGeneratorOptions o;
    o.resolution = 0.025;
    o.num_headings = headings;
    o.turning_radius = 0.3;
    o.allow_reverse = true;
    o.generator = headings == 16 ? PrimitiveGenerator::kLegacy : PrimitiveGenerator::kNearMinimal;
    const PrimitiveSet s = generatePrimitives(o);
    const std::string path = dir + "/g" + std::to_string(headings) + ".mprim";
    writeMprimFile(path, s);
    const PrimitiveSet r = readMprimFile(path, 0.025);
    ASSERT_EQ(r.primitives.size(), s.primitives.size());
    EXPECT_EQ(r.uniform, s.uniform);
    for (int h = 0; h < headings; ++h) EXPECT_NEAR(r.heading_angles[h], s.heading_angles[h], 1e-9);
    for (std::size_t i = 0; i < s.primitives.size(); ++i) {
      const MotionPrimitive& a = s.primitives[i];
      const MotionPrimitive& b = r.primitives[i];
      EXPECT_EQ(a.id, b.id);
      EXPECT_EQ(a.start_heading, b.start_heading);
      EXPECT_EQ(a.end_dx, b.end_dx);
      EXPECT_EQ(a.end_dy, b.end_dy);
      EXPECT_EQ(a.end_heading, b.end_heading);
      EXPECT_DOUBLE_EQ(a.cost_multiplier, b.cost_multiplier);
      if (!s.uniform) {  // only non-uniform files carry the turning radius
        EXPECT_NEAR(a.turning_radius, b.turning_radius, 1e-6);
      }
      ASSERT_EQ(a.poses.size(), b.poses.size());
      for (std::size_t k = 0; k < a.poses.size(); ++k) {
        EXPECT_NEAR(a.poses[k].x, b.poses[k].x, 1e-6);
        EXPECT_NEAR(a.poses[k].y, b.poses[k].y, 1e-6);
        EXPECT_NEAR(angleDistance(a.poses[k].theta, b.poses[k].theta), 0.0, 1e-6);
      }
    }
  }
}

}  // namespace
}  // namespace lattice
}  // namespace amha
