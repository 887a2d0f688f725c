#include "radiosity/cli/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace rad::cli {
namespace {

constexpr double kWidth = 720, kHeight = 460, kLeft = 80, kRight = 200, kTop = 40, kBottom = 60;
constexpr double kPlotW = kWidth - kLeft - kRight, kPlotH = kHeight - kTop - kBottom;
const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b"};

/// x as printf's %g writes it.
std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

/// Round ticks for [0, xMax]: a step of 1, 2 or 5 times a power of ten, at most six of them.
double tickStep(double xMax) {
  const double step = std::pow(10.0, std::floor(std::log10(xMax / 5)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (xMax / (m * step) <= 6) return step * m;
  return step;
}

/// The axes' ranges: x from 0 to a whole number of ticks, y over whole decades, and the
/// mapping of data to picture coordinates.
struct Axes {
  double xMax = 0, step = 1, lo = 0, hi = 1;

  explicit Axes(const std::vector<Series>& series) {
    double yMin = HUGE_VAL, yMax = 0;
    for (const auto& s : series)
      for (const auto& [x, y] : s.points)
        if (y > 0) xMax = std::max(xMax, x), yMin = std::min(yMin, y), yMax = std::max(yMax, y);
    if (!(yMax > 0)) yMin = 1e-4, yMax = 1;
    if (!(xMax > 0)) xMax = 1;
    step = tickStep(xMax);
    xMax = std::ceil(xMax / step - 1e-9) * step;
    lo = std::floor(std::log10(yMin)), hi = std::ceil(std::log10(yMax));
    if (hi <= lo) hi = lo + 1;
  }

  /// Picture x of data x.
  double px(double x) const { return kLeft + x / xMax * kPlotW; }
  /// Picture y of data y (> 0), on the logarithmic scale.
  double py(double y) const { return kTop + (hi - std::log10(y)) / (hi - lo) * kPlotH; }
};

/// The SVG element, the white background and the title.
void writeHeader(std::ostringstream& svg, const std::string& title) {
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << kWidth << "' height='" << kHeight
      << "' font-family='sans-serif' font-size='12'>\n<rect width='100%' height='100%' fill='white'/>\n";
  svg << "<text x='" << kWidth / 2 - kRight / 2 << "' y='22' text-anchor='middle' font-size='15'>" << title << "</text>\n";
}

/// Axes, decade grid lines and x ticks.
void writeGrid(std::ostringstream& svg, const Axes& a) {
  for (double d = a.lo; d <= a.hi; ++d) {
    double y = a.py(std::pow(10.0, d));
    svg << "<line x1='" << kLeft << "' y1='" << y << "' x2='" << kLeft + kPlotW << "' y2='" << y
        << "' stroke='#ddd'/>\n<text x='" << kLeft - 6 << "' y='" << y + 4
        << "' text-anchor='end'>1e" << number(d) << "</text>\n";
  }
  for (double x = 0; x <= a.xMax * (1 + 1e-9); x += a.step) {
    svg << "<text x='" << a.px(x) << "' y='" << kTop + kPlotH + 18 << "' text-anchor='middle'>"
        << number(std::round(x * 1000) / 1000) << "</text>\n";
  }
}

/// The plot's frame and the axis labels.
void writeFrame(std::ostringstream& svg, const std::string& xLabel, const std::string& yLabel) {
  svg << "<rect x='" << kLeft << "' y='" << kTop << "' width='" << kPlotW << "' height='" << kPlotH
      << "' fill='none' stroke='black'/>\n";
  svg << "<text x='" << kLeft + kPlotW / 2 << "' y='" << kHeight - 18 << "' text-anchor='middle'>" << xLabel << "</text>\n";
  svg << "<text transform='translate(22," << kTop + kPlotH / 2 << ") rotate(-90)' text-anchor='middle'>" << yLabel << "</text>\n";
}

/// Series i's polyline (its points with y > 0) and its legend entry.
void writeSeries(std::ostringstream& svg, const Axes& a, const Series& s, size_t i) {
  const char* colour = kColours[i % 6];
  svg << "<polyline fill='none' stroke-width='2' stroke='" << colour << "' points='";
  for (const auto& [x, y] : s.points)
    if (y > 0) svg << a.px(x) << "," << a.py(y) << " ";
  svg << "'/>\n";
  double ly = kTop + 14 + 20 * double(i);
  svg << "<line x1='" << kWidth - kRight + 14 << "' y1='" << ly << "' x2='" << kWidth - kRight + 38
      << "' y2='" << ly << "' stroke-width='2' stroke='" << colour << "'/>\n<text x='"
      << kWidth - kRight + 44 << "' y='" << ly + 4 << "'>" << s.name << "</text>\n";
}

}  // namespace

std::string svgLogPlot(const std::string& title, const std::string& xLabel,
                       const std::string& yLabel, const std::vector<Series>& series) {
  const Axes axes(series);
  std::ostringstream svg;
  writeHeader(svg, title);
  writeGrid(svg, axes);
  writeFrame(svg, xLabel, yLabel);
  // One polyline per series, and the legend.
  for (size_t i = 0; i < series.size(); ++i) writeSeries(svg, axes, series[i], i);
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace rad::cli
