#include "lattice_image.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "amha_planner/lattice/image_file.h"

namespace amha {
namespace cli {

namespace {
constexpr int kShift = 4;  // sub-pixel bits for OpenCV drawing

// The cells of `crop` (cells; row 0 at the bottom of the map) as pixels, `scale` per cell.
cv::Mat mapPixels(const lattice::GridMap& map, const cv::Rect& crop, int scale) {
  cv::Mat img(crop.height * scale, crop.width * scale, CV_8UC3);
  for (int y = crop.y; y < crop.y + crop.height; ++y) {
    for (int x = crop.x; x < crop.x + crop.width; ++x) {
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
      const int row = crop.y + crop.height - 1 - y;
      img(cv::Rect((x - crop.x) * scale, row * scale, scale, scale))
          .setTo(cv::Scalar(colour[0], colour[1], colour[2]));
    }
  }
  return img;
}

// Map-frame point -> sub-pixel position in an image of `crop`.
struct PixelOf {
  const lattice::GridMap& map;
  cv::Rect crop;
  int scale;
  cv::Point operator()(double wx, double wy) const {
    const double co = std::cos(map.origin_yaw), so = std::sin(map.origin_yaw);
    const double dx = wx - map.origin_x, dy = wy - map.origin_y;
    const double gx = (co * dx + so * dy) / map.resolution - crop.x,
                 gy = (-so * dx + co * dy) / map.resolution - crop.y;
    return cv::Point(static_cast<int>(std::lround(gx * scale * (1 << kShift))),
                     static_cast<int>(std::lround((crop.height - gy) * scale * (1 << kShift))));
  }
};

void drawMarker(cv::Mat& img, const PixelOf& pixel, const lattice::Pose2D& p, int scale,
                const cv::Scalar& colour) {
  const cv::Point c = pixel(p.x, p.y);
  const int r = std::max(3, 2 * scale) << kShift;
  cv::circle(img, c, r, colour, 2, cv::LINE_AA, kShift);
  const cv::Point tip(c.x + static_cast<int>(r * 2 * std::cos(p.theta)),
                      c.y - static_cast<int>(r * 2 * std::sin(p.theta)));
  cv::line(img, c, tip, colour, 2, cv::LINE_AA, kShift);
}

}  // namespace

void writePlanImage(const std::string& png, const lattice::GridMap& map,
                    const std::vector<std::vector<lattice::Pose2D>>& paths,
                    const FootprintFn& footprint_at, const lattice::Pose2D& start,
                    const lattice::Pose2D& goal) {
  const int scale = std::max(1, std::min(16, 800 / std::max(map.width, map.height)));
  cv::Mat img = mapPixels(map, cv::Rect(0, 0, map.width, map.height), scale);
  const PixelOf pixel{map, cv::Rect(0, 0, map.width, map.height), scale};
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
      if (poly.size() >= 3)
        cv::polylines(img, std::vector<std::vector<cv::Point>>{poly}, true, cv::Scalar(90, 170, 60),
                      1, cv::LINE_AA, kShift);
    }
  }
  for (std::size_t k = 0; k < paths.size(); ++k) {
    const double t = paths.size() == 1 ? 1.0 : static_cast<double>(k) / (paths.size() - 1);
    // Dark blue (first) to bright orange (last).
    const cv::Scalar colour(180 * (1 - t) + 0 * t, 40 * (1 - t) + 140 * t, 60 * (1 - t) + 255 * t);
    std::vector<cv::Point> line;
    for (const auto& p : paths[k]) line.push_back(pixel(p.x, p.y));
    if (line.size() >= 2) {
      cv::polylines(img, std::vector<std::vector<cv::Point>>{line}, false, colour,
                    k + 1 == paths.size() ? thick + 1 : thick, cv::LINE_AA, kShift);
    }
  }
  drawMarker(img, pixel, start, scale, cv::Scalar(0, 160, 0));
  drawMarker(img, pixel, goal, scale, cv::Scalar(0, 0, 220));
  lattice::writeImageFile(png, img);  // throws "cannot write <path>..."
}

void writePathsImage(const std::string& png, const lattice::GridMap& map,
                     const std::vector<LabelledPath>& paths, const lattice::Pose2D& start,
                     const lattice::Pose2D& goal, double margin_m) {
  // The cells around the paths (and the start and goal), in grid coordinates.
  const double co = std::cos(map.origin_yaw), so = std::sin(map.origin_yaw);
  double x0 = 1e18, y0 = 1e18, x1 = -1e18, y1 = -1e18;
  auto include = [&](const lattice::Pose2D& p) {
    const double dx = p.x - map.origin_x, dy = p.y - map.origin_y;
    const double gx = (co * dx + so * dy) / map.resolution,
                 gy = (-so * dx + co * dy) / map.resolution;
    x0 = std::min(x0, gx), y0 = std::min(y0, gy), x1 = std::max(x1, gx), y1 = std::max(y1, gy);
  };
  include(start);
  include(goal);
  for (const LabelledPath& p : paths)
    for (const auto& q : p.poses) include(q);
  const double m = margin_m / map.resolution;
  const int cx0 = std::max(0, static_cast<int>(x0 - m)),
            cy0 = std::max(0, static_cast<int>(y0 - m));
  const int cx1 = std::min(map.width, static_cast<int>(x1 + m) + 1),
            cy1 = std::min(map.height, static_cast<int>(y1 + m) + 1);
  const cv::Rect crop(cx0, cy0, std::max(1, cx1 - cx0), std::max(1, cy1 - cy0));
  const int scale = std::max(1, std::min(16, 900 / std::max(crop.width, crop.height)));
  cv::Mat img = mapPixels(map, crop, scale);
  const PixelOf pixel{map, crop, scale};
  // Earlier paths wider, so that later ones drawn over them leave them visible.
  for (std::size_t k = 0; k < paths.size(); ++k) {
    const cv::Scalar colour(paths[k].bgr[0], paths[k].bgr[1], paths[k].bgr[2]);
    std::vector<cv::Point> line;
    for (const auto& p : paths[k].poses) line.push_back(pixel(p.x, p.y));
    const int width = 2 + 2 * static_cast<int>(paths.size() - 1 - k);
    if (line.size() >= 2)
      cv::polylines(img, std::vector<std::vector<cv::Point>>{line}, false, colour, width,
                    cv::LINE_AA, kShift);
  }
  drawMarker(img, pixel, start, scale, cv::Scalar(0, 160, 0));
  drawMarker(img, pixel, goal, scale, cv::Scalar(0, 0, 220));
  // The legend last, on white, so that nothing covers it.
  for (std::size_t k = 0; k < paths.size(); ++k) {
    int baseline = 0;
    const cv::Size text =
        cv::getTextSize(paths[k].label, cv::FONT_HERSHEY_SIMPLEX, 0.5, 1, &baseline);
    const cv::Point at(10, 24 + 22 * static_cast<int>(k));
    cv::rectangle(img, at + cv::Point(-4, -text.height - 4),
                  at + cv::Point(text.width + 4, baseline + 2), cv::Scalar(255, 255, 255),
                  cv::FILLED);
    cv::putText(img, paths[k].label, at, cv::FONT_HERSHEY_SIMPLEX, 0.5,
                cv::Scalar(paths[k].bgr[0], paths[k].bgr[1], paths[k].bgr[2]), 1, cv::LINE_AA);
  }
  lattice::writeImageFile(png, img);
}

}  // namespace cli
}  // namespace amha
