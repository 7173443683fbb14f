// The image codecs module (image_file.h): a process that plans on an SBPL .cfg map never maps
// OpenCV's imgcodecs (nor our module); one that loads a map_server YAML + PGM map does; the
// loader's round trips, errors and thread-safe first use. This executable links amha_lattice
// and opencv_core only (no imgcodecs), so /proc/self/maps shows what the code loaded.
// Tests about "first use" run in a fresh child process (a threadsafe-style death test re-runs
// this executable), so that they do not depend on the order the tests run in.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "amha_planner/lattice/image_file.h"
#include "amha_planner/lattice/lattice_planner.h"
#include "amha_planner/lattice/map_loaders.h"
#include "test_support.h"

namespace amha {
namespace lattice {
namespace {

bool mapped(const std::string& library) {
  std::ifstream maps("/proc/self/maps");
  std::string line;
  while (std::getline(maps, line)) {
    if (line.find(library) != std::string::npos) return true;
  }
  return false;
}

void writeFile(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
}

// Runs `check` in a child process (this executable again, threadsafe style); the child exits 0
// if it returned "" and 1 after printing its message otherwise.
template <typename Check>
void inFreshProcess(Check check) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        std::string failure;
        try {
          failure = check();
        } catch (const std::exception& e) {
          failure = std::string("exception: ") + e.what();
        }
        if (!failure.empty()) std::fprintf(stderr, "FAILED: %s\n", failure.c_str());
        std::exit(failure.empty() ? 0 : 1);
      },
      ::testing::ExitedWithCode(0), "");
}

const char* const kImgcodecs = "libopencv_imgcodecs";
const char* const kModule = "libamha_image_codecs";

// 40 x 30 cells of 0.1 m, a wall at x = 2.0 m with a gap at the top; start and end below it
// on either side.
std::string writeCfg(const std::string& dir) {
  std::ostringstream f;
  f << "discretization(cells): 40 30\nobsthresh: 254\ncost_inscribed_thresh: 253\n"
       "cost_possibly_circumscribed_thresh: 128\ncellsize(meters): 0.1\nnominalvel(mpersecs): 1.0\n"
       "timetoturn45degsinplace(secs): 1.0\nstart(meters,rads): 0.5 0.5 0\n"
       "end(meters,rads): 3.5 0.5 0\nenvironment:\n";
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < 40; ++x) f << (x > 0 ? " " : "") << (x == 20 && y < 20 ? 254 : 0);
    f << "\n";
  }
  writeFile(dir + "/wall.cfg", f.str());
  return dir + "/wall.cfg";
}

TEST(ImageCodecsModule, NotLoadedToPlanOnCfgMapsLoadedForYamlImageMaps) {
  inFreshProcess([]() -> std::string {
    if (mapped(kImgcodecs)) return "imgcodecs is mapped before anything was loaded (linked in?)";
    if (mapped(kModule)) return "the module is mapped before anything was loaded";
    const std::string dir = test::tempDir();
    const SbplEnvironment env = loadSbplEnvironment(writeCfg(dir));
    LatticeConfig config;
    config.robot.radius = 0.1;
    LatticePlanner planner(std::make_shared<GridMap>(env.map), config);
    SearchLimits limits;
    limits.time_limit_s = 30.0;
    const PlanResult r =
        planner.plan(env.start, env.goal, defaultConfig(Algorithm::kAraStar), limits);
    if (r.error != QueryError::kNone) return "query refused: " + r.message;
    if (r.solutions.empty()) return "no path on the .cfg map";
    if (mapped(kImgcodecs) || mapped(kModule))
      return "planning on a .cfg map loaded the image codecs";

    // A map_server map: 3 x 2 pixels, top row black (occupied), bottom row white (free).
    writeFile(dir + "/m.pgm", std::string("P5\n3 2\n255\n\x00\x00\x00\xff\xff\xff", 17));
    writeFile(dir + "/m.yaml",
              "image: m.pgm\nresolution: 0.5\norigin: [0, 0, 0]\nnegate: 0\n"
              "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
    const GridMap m = loadMapServerMap(dir + "/m.yaml");
    if (m.width != 3 || m.height != 2) return "the PGM map has the wrong size";
    if (m.at(0, 0) != kFreeCost || m.at(2, 1) != kLethalCost)
      return "the PGM map has the wrong costs";
    if (!mapped(kModule)) return "the module is not mapped after reading a PGM map";
    if (!mapped(kImgcodecs)) return "imgcodecs is not mapped after reading a PGM map";
    return "";
  });
}

TEST(ImageFile, RoundTripsAndErrors) {
  const std::string dir = test::tempDir();
  cv::Mat grey(5, 7, CV_8UC1), colour(5, 7, CV_8UC3);
  cv::randu(grey, 0, 256);
  cv::randu(colour, 0, 256);
  writeImageFile(dir + "/g.png", grey);
  writeImageFile(dir + "/c.png", colour);
  const cv::Mat g = readImageFile(dir + "/g.png");
  ASSERT_EQ(g.type(), CV_8UC1);
  EXPECT_EQ(cv::norm(g, grey, cv::NORM_INF), 0.0);
  const cv::Mat c = readImageFile(dir + "/c.png", ImageReadMode::kAsIs);
  ASSERT_EQ(c.type(), CV_8UC3);
  EXPECT_EQ(cv::norm(c, colour, cv::NORM_INF), 0.0);
  const cv::Mat cg = readImageFile(dir + "/c.png", ImageReadMode::kGrey);
  EXPECT_EQ(cg.type(), CV_8UC1);
  EXPECT_EQ(cg.size(), colour.size());
  EXPECT_TRUE(mapped(kModule));
  EXPECT_NE(imageCodecsModulePath().find("/libamha_image_codecs.so"), std::string::npos);

  // As cv::imread: an empty image for a missing or undecodable file.
  EXPECT_TRUE(readImageFile(dir + "/missing.png").empty());
  writeFile(dir + "/junk.png", "not an image");
  EXPECT_TRUE(readImageFile(dir + "/junk.png").empty());
  // Writing: imwrite's false, and OpenCV's exception (no writer for the extension), as errors
  // naming the file; no exception type of OpenCV's crosses the module boundary.
  try {
    writeImageFile(dir + "/no/such/dir/x.png", grey);
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "cannot write " + dir + "/no/such/dir/x.png");
  }
  try {
    writeImageFile(dir + "/x.unknown_format", grey);
    ADD_FAILURE() << "no exception";
  } catch (const cv::Exception&) {
    ADD_FAILURE() << "cv::Exception crossed the module boundary";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("cannot write " + dir + "/x.unknown_format: ", 0), 0u)
        << e.what();
  }
}

// Eight threads whose first calls race to load the module. Not named "Concurrent": the TSan
// pass of scripts/test runs those, and any imread under TSan reports a lock-order inversion
// inside GDAL (which imgcodecs loads, uninstrumented), even from a single thread. The next test
// races the loader itself under TSan without calling OpenCV.
TEST(ImageFile, ParallelFirstUse) {
  inFreshProcess([]() -> std::string {
    const std::string dir = test::tempDir();
    writeFile(dir + "/m.pgm", std::string("P5\n2 1\n255\n\x10\x20", 13));
    std::vector<int> ok(8, 0);
    std::vector<std::thread> threads;
    for (std::size_t i = 0; i < ok.size(); ++i) {
      threads.emplace_back([&, i] {
        const cv::Mat m = readImageFile(dir + "/m.pgm");
        ok[i] = m.cols == 2 && m.rows == 1 && m.at<std::uint8_t>(0, 1) == 0x20;
      });
    }
    for (auto& t : threads) t.join();
    for (int v : ok) {
      if (!v) return "a thread read a wrong image";
    }
    return "";
  });
}

TEST(ImageFile, ConcurrentFirstUseOfAMissingModule) {
  inFreshProcess([]() -> std::string {
    setenv("AMHA_IMAGE_CODECS_MODULE", "/nonexistent/libamha_image_codecs.so", 1);
    std::vector<std::string> messages(8);
    std::vector<std::thread> threads;
    for (std::size_t i = 0; i < messages.size(); ++i) {
      threads.emplace_back([&, i] {
        try {
          writeImageFile("/tmp/never_written.png", cv::Mat(1, 1, CV_8UC1));
        } catch (const ImageCodecsUnavailable& e) {
          messages[i] = e.what();
        }
      });
    }
    for (auto& t : threads) t.join();
    for (const auto& m : messages) {
      if (m.rfind("cannot load image codecs module /nonexistent/libamha_image_codecs.so: ", 0) !=
          0) {
        return "unexpected error: '" + m + "'";
      }
    }
    return "";
  });
}

TEST(ImageFile, ModuleThatCannotBeLoadedIsAClearError) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const std::string dir = test::tempDir();
  writeFile(dir + "/m.pgm", std::string("P5\n2 1\n255\n\x10\x20", 13));
  writeFile(dir + "/m.yaml",
            "image: m.pgm\nresolution: 0.5\norigin: [0, 0, 0]\nnegate: 0\n"
            "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  writeFile(dir + "/not_a_library.so", "not an ELF file");
  // The child reads the override at its first use of the module.
  auto tryLoad = [&](const std::string& module) {
    setenv("AMHA_IMAGE_CODECS_MODULE", module.c_str(), 1);
    try {
      readImageFile(dir + "/m.pgm");
    } catch (const ImageCodecsUnavailable& e) {
      std::fprintf(stderr, "%s\n", e.what());
    }
    try {
      loadMapServerMap(dir + "/m.yaml");
    } catch (const LatticeError& e) {
      std::fprintf(stderr, "%s\n", e.what());
      std::exit(e.kind() == LatticeError::Kind::kMap ? 3 : 4);
    }
    std::exit(0);
  };
  EXPECT_EXIT(tryLoad(dir + "/missing.so"), ::testing::ExitedWithCode(3),
              "cannot load image codecs module .*/missing.so: .*No such file or directory\n"
              ".*/m.pgm: cannot read the image: cannot load image codecs module .*/missing.so");
  EXPECT_EXIT(
      tryLoad(dir + "/not_a_library.so"), ::testing::ExitedWithCode(3),
      "cannot load image codecs module .*/not_a_library.so: .*(invalid ELF header|too short)");
}

}  // namespace
}  // namespace lattice
}  // namespace amha
