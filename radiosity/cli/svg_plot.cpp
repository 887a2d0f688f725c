#include "radiosity/cli/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace rad::cli {
namespace {

constexpr double kWidth = 720, kHeight = 460, kLeft = 80, kRight = 200, kTop = 40, kBottom = 60;
const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b"};

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

}  // namespace

std::string svgLogPlot(const std::string& title, const std::string& xLabel,
                       const std::string& yLabel, const std::vector<Series>& series) {
  double xMax = 0, yMin = HUGE_VAL, yMax = 0;
  for (const auto& s : series)
    for (const auto& [x, y] : s.points)
      if (y > 0) xMax = std::max(xMax, x), yMin = std::min(yMin, y), yMax = std::max(yMax, y);
  if (!(yMax > 0)) yMin = 1e-4, yMax = 1;
  if (!(xMax > 0)) xMax = 1;
  // Round ticks: a step of 1, 2 or 5 times a power of ten, at most six of them.
  double step = std::pow(10.0, std::floor(std::log10(xMax / 5)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (xMax / (m * step) <= 6) {
      step *= m;
      break;
    }
  xMax = std::ceil(xMax / step - 1e-9) * step;
  double lo = std::floor(std::log10(yMin)), hi = std::ceil(std::log10(yMax));
  if (hi <= lo) hi = lo + 1;
  const double plotW = kWidth - kLeft - kRight, plotH = kHeight - kTop - kBottom;
  auto px = [&](double x) { return kLeft + x / xMax * plotW; };
  auto py = [&](double y) { return kTop + (hi - std::log10(y)) / (hi - lo) * plotH; };

  std::ostringstream svg;
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << kWidth << "' height='" << kHeight
      << "' font-family='sans-serif' font-size='12'>\n<rect width='100%' height='100%' fill='white'/>\n";
  svg << "<text x='" << kWidth / 2 - kRight / 2 << "' y='22' text-anchor='middle' font-size='15'>" << title << "</text>\n";
  // Axes, decade grid lines and x ticks.
  for (double d = lo; d <= hi; ++d) {
    double y = py(std::pow(10.0, d));
    svg << "<line x1='" << kLeft << "' y1='" << y << "' x2='" << kLeft + plotW << "' y2='" << y
        << "' stroke='#ddd'/>\n<text x='" << kLeft - 6 << "' y='" << y + 4
        << "' text-anchor='end'>1e" << number(d) << "</text>\n";
  }
  for (double x = 0; x <= xMax * (1 + 1e-9); x += step) {
    svg << "<text x='" << px(x) << "' y='" << kTop + plotH + 18 << "' text-anchor='middle'>"
        << number(std::round(x * 1000) / 1000) << "</text>\n";
  }
  svg << "<rect x='" << kLeft << "' y='" << kTop << "' width='" << plotW << "' height='" << plotH
      << "' fill='none' stroke='black'/>\n";
  svg << "<text x='" << kLeft + plotW / 2 << "' y='" << kHeight - 18 << "' text-anchor='middle'>" << xLabel << "</text>\n";
  svg << "<text transform='translate(22," << kTop + plotH / 2 << ") rotate(-90)' text-anchor='middle'>" << yLabel << "</text>\n";
  // One polyline per series, and the legend.
  for (size_t i = 0; i < series.size(); ++i) {
    const char* colour = kColours[i % 6];
    svg << "<polyline fill='none' stroke-width='2' stroke='" << colour << "' points='";
    for (const auto& [x, y] : series[i].points)
      if (y > 0) svg << px(x) << "," << py(y) << " ";
    svg << "'/>\n";
    double ly = kTop + 14 + 20 * double(i);
    svg << "<line x1='" << kWidth - kRight + 14 << "' y1='" << ly << "' x2='" << kWidth - kRight + 38
        << "' y2='" << ly << "' stroke-width='2' stroke='" << colour << "'/>\n<text x='"
        << kWidth - kRight + 44 << "' y='" << ly + 4 << "'>" << series[i].name << "</text>\n";
  }
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace rad::cli
