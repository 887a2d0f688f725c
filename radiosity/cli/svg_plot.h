#pragma once
// A small line plot as SVG: linear x, logarithmic y, one polyline per series, a legend.
#include <string>
#include <utility>
#include <vector>

namespace rad::cli {

struct Series {
  std::string name;
  std::vector<std::pair<double, double>> points;  ///< (x, y), y > 0
};

/// The SVG text of the plot.
std::string svgLogPlot(const std::string& title, const std::string& xLabel,
                       const std::string& yLabel, const std::vector<Series>& series);

}  // namespace rad::cli
