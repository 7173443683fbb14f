#include "lattice_image.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "amha_planner/lattice/image_file.h"

namespace amha {
namespace cli {

namespace {

constexpr int kShift = 4;  // sub-pixel bits for OpenCV drawing

// The map cells [x0, x0 + w) x [y0, y0 + h), `scale` pixels per cell, and the map -> pixel
// mapping (kShift sub-pixel bits).
struct MapPicture {
  cv::Mat img;
  std::function<cv::Point(double, double)> pixel;
};

MapPicture drawMap(const lattice::GridMap& map, int scale, int x0, int y0, int w, int h) {
  MapPicture pic;
  pic.img = cv::Mat(h * scale, w * scale, CV_8UC3);
  for (int y = y0; y < y0 + h; ++y) {
    for (int x = x0; x < x0 + w; ++x) {
      const int c = map.at(x, y);
      cv::Vec3b colour;
      if (c == lattice::kUnknownCost) {
        colour = {200, 185, 185};
      } else if (c == lattice::kLethalCost) {
        colour = {0, 0, 0};
      } else if (c == lattice::kInscribedCost) {
        colour = {110, 110, 150};
      } else {
        const int v = 255 - c * 120 / 252;
        colour = {static_cast<uchar>(v), static_cast<uchar>(v), static_cast<uchar>(v)};
      }
      pic.img(cv::Rect((x - x0) * scale, (y0 + h - 1 - y) * scale, scale, scale)).setTo(cv::Scalar(colour[0], colour[1], colour[2]));
    }
  }
  const double co = std::cos(map.origin_yaw), so = std::sin(map.origin_yaw);
  pic.pixel = [&map, co, so, scale, x0, y0, h](double wx, double wy) {
    const double dx = wx - map.origin_x, dy = wy - map.origin_y;
    const double gx = (co * dx + so * dy) / map.resolution - x0, gy = (-so * dx + co * dy) / map.resolution - y0;
    return cv::Point(static_cast<int>(std::lround(gx * scale * (1 << kShift))),
                     static_cast<int>(std::lround((h - gy) * scale * (1 << kShift))));
  };
  return pic;
}

}  // namespace

void writePlanImage(const std::string& png, const lattice::GridMap& map,
                    const std::vector<std::vector<lattice::Pose2D>>& paths, const FootprintFn& footprint_at,
                    const lattice::Pose2D& start, const lattice::Pose2D& goal) {
  const int scale = std::max(1, std::min(16, 800 / std::max(map.width, map.height)));
  MapPicture pic = drawMap(map, scale, 0, 0, map.width, map.height);
  cv::Mat& img = pic.img;
  const auto& pixel = pic.pixel;
  const int thick = std::max(1, scale / 3);
  // Footprint along the last path, about every half metre (and at its ends).
  if (!paths.empty() && footprint_at) {
    const auto& last = paths.back();
    double since = 1e9;
    for (std::size_t i = 0; i < last.size(); ++i) {
      if (i > 0) since += std::hypot(last[i].x - last[i - 1].x, last[i].y - last[i - 1].y);
      if (since < 0.5 && i + 1 != last.size()) continue;
      since = 0.0;
      std::vector<cv::Point> poly;
      for (const auto& v : footprint_at(last[i])) poly.push_back(pixel(v[0], v[1]));
      if (poly.size() >= 3) cv::polylines(img, std::vector<std::vector<cv::Point>>{poly}, true, cv::Scalar(90, 170, 60), 1, cv::LINE_AA, kShift);
    }
  }
  for (std::size_t k = 0; k < paths.size(); ++k) {
    const double t = paths.size() == 1 ? 1.0 : static_cast<double>(k) / (paths.size() - 1);
    // Dark blue (first) to bright orange (last).
    const cv::Scalar colour(180 * (1 - t) + 0 * t, 40 * (1 - t) + 140 * t, 60 * (1 - t) + 255 * t);
    std::vector<cv::Point> line;
    for (const auto& p : paths[k]) line.push_back(pixel(p.x, p.y));
    if (line.size() >= 2) {
      cv::polylines(img, std::vector<std::vector<cv::Point>>{line}, false, colour, k + 1 == paths.size() ? thick + 1 : thick, cv::LINE_AA, kShift);
    }
  }
  auto marker = [&](const lattice::Pose2D& p, const cv::Scalar& colour) {
    const cv::Point c = pixel(p.x, p.y);
    const int r = std::max(3, 2 * scale) << kShift;
    cv::circle(img, c, r, colour, 2, cv::LINE_AA, kShift);
    const cv::Point tip(c.x + static_cast<int>(r * 2 * std::cos(p.theta)), c.y - static_cast<int>(r * 2 * std::sin(p.theta)));
    cv::line(img, c, tip, colour, 2, cv::LINE_AA, kShift);
  };
  marker(start, cv::Scalar(0, 160, 0));
  marker(goal, cv::Scalar(0, 0, 220));
  lattice::writeImageFile(png, img);  // throws "cannot write <path>..."
}

void writePathsImage(const std::string& png, const lattice::GridMap& map, const std::vector<ColouredPath>& paths,
                     double margin, int max_side) {
  // The cells around the paths.
  double x0 = 1e18, y0 = 1e18, x1 = -1e18, y1 = -1e18;
  const double co = std::cos(map.origin_yaw), so = std::sin(map.origin_yaw);
  for (const ColouredPath& p : paths) {
    for (const lattice::Pose2D& q : p.poses) {
      const double dx = q.x - map.origin_x, dy = q.y - map.origin_y;
      const double gx = (co * dx + so * dy) / map.resolution, gy = (-so * dx + co * dy) / map.resolution;
      x0 = std::min(x0, gx);
      y0 = std::min(y0, gy);
      x1 = std::max(x1, gx);
      y1 = std::max(y1, gy);
    }
  }
  if (x0 > x1) throw std::runtime_error("no path to draw");
  const double m = margin / map.resolution;
  const int cx0 = std::max(0, static_cast<int>(std::floor(x0 - m))), cy0 = std::max(0, static_cast<int>(std::floor(y0 - m)));
  const int cx1 = std::min(map.width, static_cast<int>(std::ceil(x1 + m))), cy1 = std::min(map.height, static_cast<int>(std::ceil(y1 + m)));
  const int scale = std::max(1, std::min(16, max_side / std::max(cx1 - cx0, cy1 - cy0)));
  MapPicture pic = drawMap(map, scale, cx0, cy0, cx1 - cx0, cy1 - cy0);
  for (const ColouredPath& p : paths) {
    std::vector<cv::Point> line;
    for (const auto& q : p.poses) line.push_back(pic.pixel(q.x, q.y));
    if (line.size() >= 2) {
      cv::polylines(pic.img, std::vector<std::vector<cv::Point>>{line}, false, cv::Scalar(p.bgr[0], p.bgr[1], p.bgr[2]),
                    std::max(2, scale / 3), cv::LINE_AA, kShift);
    }
  }
  lattice::writeImageFile(png, pic.img);
}

}  // namespace cli
}  // namespace amha
