#include "random_map.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <random>
#include <stdexcept>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "amha_planner/lattice/image_file.h"

namespace amha {
namespace cli {

namespace {

// Uniform in [lo, hi) from the engine's raw 32-bit output (portable, unlike the distributions).
double uniform(std::mt19937& rng, double lo, double hi) {
  return lo + (hi - lo) * (rng() / 4294967296.0);
}

struct Shape {
  cv::RotatedRect box;
  bool ellipse = false;
};

// A wall (thin and long, along x or y), a turned box or an ellipse, 0.2 - 2 m; or, one time in
// four, a row of walls along x or y with gaps of 0.6 - 1.5 m between them, which makes corridors.
std::vector<Shape> randomShapes(std::mt19937& rng, const cv::Size& map, double cells_per_m) {
  cv::Point2f centre(static_cast<float>(uniform(rng, 0, map.width)),
                     static_cast<float>(uniform(rng, 0, map.height)));
  const unsigned kind = rng() % 4;
  const float angle = static_cast<float>(uniform(rng, 0.0, 180.0));
  auto metres = [&](double lo, double hi) {
    return static_cast<float>(uniform(rng, lo, hi) * cells_per_m);
  };
  std::vector<Shape> out;
  if (kind == 3) {
    const bool along_x = rng() % 2;
    const float thickness = metres(0.2, 0.35);
    for (int k = 3 + static_cast<int>(rng() % 6); k > 0; --k) {
      const float length = metres(0.8, 2.0), gap = metres(0.6, 1.5);
      (along_x ? centre.x : centre.y) += 0.5f * length;
      Shape s;
      s.box = cv::RotatedRect(
          centre, along_x ? cv::Size2f(length, thickness) : cv::Size2f(thickness, length), 0.0f);
      out.push_back(s);
      (along_x ? centre.x : centre.y) += 0.5f * length + gap;
    }
  } else if (kind == 0) {
    cv::Size2f size(metres(0.8, 2.0), metres(0.2, 0.35));
    if (rng() % 2) std::swap(size.width, size.height);
    out.push_back({cv::RotatedRect(centre, size, 0.0f), false});
  } else {
    const cv::Size2f size(metres(0.2, 1.5), metres(0.2, 1.5));
    out.push_back({cv::RotatedRect(centre, size, angle), kind == 2});
  }
  return out;
}

void draw(cv::Mat& occ, const Shape& s) {
  if (s.ellipse) {
    cv::ellipse(occ, s.box, cv::Scalar(255), cv::FILLED, cv::LINE_8);
    return;
  }
  cv::Point2f corners[4];
  s.box.points(corners);
  cv::Point poly[4];
  for (int i = 0; i < 4; ++i) poly[i] = cv::Point(cvRound(corners[i].x), cvRound(corners[i].y));
  cv::fillConvexPoly(occ, poly, 4, cv::Scalar(255), cv::LINE_8);
}

}  // namespace

RandomMap randomObstacleMap(const RandomMapOptions& o) {
  if (o.width <= 0 || o.height <= 0 ||
      static_cast<double>(o.width) * o.height > static_cast<double>(1 << 26)) {
    throw std::invalid_argument("the map must have 1 .. 2^26 cells (width and height > 0), not " +
                                std::to_string(o.width) + " x " + std::to_string(o.height));
  }
  if (!(o.resolution >= 1e-3 && o.resolution <= 1e3)) {
    throw std::invalid_argument("the resolution must be in [0.001, 1000] m, not " +
                                std::to_string(o.resolution));
  }
  if (!(o.obstacle_fraction >= 0.0 && o.obstacle_fraction <= 0.9)) {
    throw std::invalid_argument("the obstacle fraction must be in [0, 0.9], not " +
                                std::to_string(o.obstacle_fraction));
  }
  RandomMap out;
  out.occupied = cv::Mat::zeros(o.height, o.width, CV_8U);
  cv::Mat& occ = out.occupied;
  std::mt19937 rng(o.seed);
  const double cells = static_cast<double>(o.width) * o.height,
               target = o.obstacle_fraction * cells;
  const cv::Rect whole(0, 0, o.width, o.height);
  double filled = 0.0;
  // Each shape adds the cells it newly covers, counted inside its own box: exact and cheap.
  while (filled < target) {
    const std::vector<Shape> shapes = randomShapes(rng, occ.size(), 1.0 / o.resolution);
    cv::Rect box;
    for (const Shape& s : shapes) box |= s.box.boundingRect();
    box = (box - cv::Point(1, 1) + cv::Size(2, 2)) & whole;
    const int before = box.area() > 0 ? cv::countNonZero(occ(box)) : 0;
    for (const Shape& s : shapes) draw(occ, s);
    filled += (box.area() > 0 ? cv::countNonZero(occ(box)) : 0) - before;
    out.obstacles += static_cast<int>(shapes.size());
  }
  // Free cells outside the largest 4-connected free region are pockets no query could use.
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(occ == 0, labels, stats, centroids, 4, CV_32S);
  int largest = 0;
  for (int i = 1; i < n; ++i) {
    if (largest == 0 ||
        stats.at<int>(i, cv::CC_STAT_AREA) > stats.at<int>(largest, cv::CC_STAT_AREA))
      largest = i;
  }
  for (int i = 1; i < n; ++i) {
    if (i != largest) out.pocket_cells += stats.at<int>(i, cv::CC_STAT_AREA);
  }
  if (out.pocket_cells > 0) occ.setTo(255, (labels != largest) & (occ == 0));
  out.occupied_fraction = cv::countNonZero(occ) / cells;
  return out;
}

void writeMapServerFiles(const std::string& base, const cv::Mat& occupied, double resolution) {
  cv::Mat image(occupied.size(), CV_8U, cv::Scalar(254));
  image.setTo(0, occupied);
  lattice::writeImageFile(base + ".pgm", image);
  const std::size_t slash = base.find_last_of('/');
  const std::string image_name =
      (slash == std::string::npos ? base : base.substr(slash + 1)) + ".pgm";
  std::ofstream yaml(base + ".yaml");
  yaml << std::setprecision(12) << "image: " << image_name << "\nresolution: " << resolution
       << "\norigin: [0.0, 0.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
  yaml.flush();
  if (!yaml) throw std::runtime_error("cannot write " + base + ".yaml");
}

}  // namespace cli
}  // namespace amha
