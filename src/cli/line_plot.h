// Line charts as PNG (OpenCV), for the benchmarks' cost / bound vs time figures.
#pragma once

#include <string>
#include <vector>

namespace amha {
namespace cli {

struct PlotSeries {
  std::string label;
  std::vector<double> x, y;  // same length; non-finite points are skipped
  bool steps = true;         // anytime curves are step functions: hold y until the next x
};

struct PlotOptions {
  std::string title, x_label, y_label;
  bool log_x = false, log_y = false;
  int width = 960, height = 600;
};

/// Draws the series with axes, ticks, labels and a legend. Throws std::runtime_error if the
/// file cannot be written or no series has a finite point.
void writeLinePlot(const std::string& png_path, const std::vector<PlotSeries>& series,
                   const PlotOptions& options);

}  // namespace cli
}  // namespace amha
