#include "line_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "amha_planner/lattice/image_file.h"

namespace amha {
namespace cli {

namespace {

const cv::Scalar kColors[] = {{200, 80, 30},  {40, 40, 220},   {40, 160, 40}, {180, 60, 180},
                              {20, 150, 220}, {120, 120, 120}, {160, 160, 0}, {0, 0, 0}};

struct Axis {
  double lo, hi;
  bool log;
  double map(double v, double a, double b) const {  // value -> pixel between a and b
    const double t = log ? (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo))
                         : (v - lo) / (hi - lo);
    return a + t * (b - a);
  }
  std::vector<double> ticks() const {
    std::vector<double> t;
    if (log) {
      // Decades; over a narrow range (fewer than 3 decades) also 2x and 5x each decade.
      const bool narrow = std::log10(hi) - std::log10(lo) < 3.0;
      for (double d = std::pow(10.0, std::floor(std::log10(lo))); d <= hi * 1.0001; d *= 10) {
        for (double m : {1.0, 2.0, 5.0}) {
          if (m != 1.0 && !narrow) continue;
          const double v = d * m;
          if (v >= lo * 0.9999 && v <= hi * 1.0001) t.push_back(v);
        }
      }
      if (t.size() < 2) t = {lo, hi};
      return t;
    }
    const double raw = (hi - lo) / 6.0;
    const double mag = std::pow(10.0, std::floor(std::log10(raw)));
    double step = mag;
    for (double m : {1.0, 2.0, 5.0, 10.0}) {
      if (raw <= m * mag) {
        step = m * mag;
        break;
      }
    }
    for (double v = std::ceil(lo / step) * step; v <= hi + step * 1e-6; v += step) t.push_back(v);
    return t;
  }
};

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%g", v);
  return buf;
}

Axis makeAxis(const std::vector<PlotSeries>& series, bool use_x, bool log) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& s : series) {
    for (double v : use_x ? s.x : s.y) {
      if (!std::isfinite(v) || (log && v <= 0)) continue;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  if (!std::isfinite(lo)) throw std::runtime_error("plot has no finite points");
  if (hi <= lo) {
    hi = lo + (log ? lo : 1.0);
    if (!log) lo -= 1.0;
  }
  if (!log) {
    const double pad = 0.05 * (hi - lo);
    lo -= pad;
    hi += pad;
  }
  return Axis{lo, hi, log};
}

}  // namespace

void writeLinePlot(const std::string& png_path, const std::vector<PlotSeries>& series,
                   const PlotOptions& o) {
  cv::Mat img(o.height, o.width, CV_8UC3, cv::Scalar(255, 255, 255));
  const Axis ax = makeAxis(series, true, o.log_x), ay = makeAxis(series, false, o.log_y);
  const int left = 90, right = o.width - 200, top = 64, bottom = o.height - 70;
  const auto font = cv::FONT_HERSHEY_SIMPLEX;
  const cv::Scalar black(0, 0, 0), grid(225, 225, 225);

  for (double t : ax.ticks()) {
    const int px = static_cast<int>(ax.map(t, left, right));
    cv::line(img, {px, top}, {px, bottom}, grid, 1);
    cv::putText(img, fmt(t), {px - 15, bottom + 20}, font, 0.45, black, 1, cv::LINE_AA);
  }
  for (double t : ay.ticks()) {
    const int py = static_cast<int>(ay.map(t, bottom, top));
    cv::line(img, {left, py}, {right, py}, grid, 1);
    cv::putText(img, fmt(t), {8, py + 5}, font, 0.45, black, 1, cv::LINE_AA);
  }
  cv::rectangle(img, {left, top}, {right, bottom}, black, 1);
  cv::putText(img, o.title, {left, 26}, font, 0.65, black, 1, cv::LINE_AA);
  cv::putText(img, o.x_label, {(left + right) / 2 - 60, o.height - 25}, font, 0.55, black, 1,
              cv::LINE_AA);
  cv::putText(img, o.y_label, {8, top - 12}, font, 0.5, black, 1, cv::LINE_AA);

  const cv::Rect clip(left, top, right - left + 1, bottom - top + 1);
  int legend_y = top + 10;
  for (std::size_t k = 0; k < series.size(); ++k) {
    const auto& s = series[k];
    const cv::Scalar color = kColors[k % (sizeof(kColors) / sizeof(kColors[0]))];
    std::vector<cv::Point> pts;
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      if ((o.log_x && s.x[i] <= 0) || (o.log_y && s.y[i] <= 0)) continue;
      const cv::Point p(static_cast<int>(ax.map(s.x[i], left, right)),
                        static_cast<int>(ay.map(s.y[i], bottom, top)));
      if (s.steps && !pts.empty()) pts.emplace_back(p.x, pts.back().y);
      pts.push_back(p);
    }
    for (std::size_t i = 1; i < pts.size(); ++i) {
      cv::Point a = pts[i - 1], b = pts[i];
      if (cv::clipLine(clip, a, b)) cv::line(img, a, b, color, 2, cv::LINE_AA);
    }
    for (const auto& p : pts) {
      if (clip.contains(p)) cv::circle(img, p, 3, color, cv::FILLED, cv::LINE_AA);
    }
    cv::line(img, {right + 15, legend_y}, {right + 45, legend_y}, color, 3);
    cv::putText(img, s.label, {right + 52, legend_y + 5}, font, 0.5, black, 1, cv::LINE_AA);
    legend_y += 24;
  }
  lattice::writeImageFile(png_path, img);  // throws "cannot write <path>..."
}

}  // namespace cli
}  // namespace amha
