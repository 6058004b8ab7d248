// A log-log scatter chart as SVG text: labelled points with optional whiskers (e.g. the best and
// worst case around a median), one colour per series, decade grid lines, axis titles and a legend.
// Opens in any browser; no plotting library needed.
#pragma once

#include <string>
#include <vector>

namespace bssrdf {

struct ChartPoint {
  std::string label;             // written beside the point (may be empty)
  double x = 0, y = 0;           // > 0 (log axes)
  double y_low = 0, y_high = 0;  // whisker ends; 0: none
};

struct ChartSeries {
  std::string name;     // legend entry
  std::string colour;   // SVG colour, e.g. "#1f77b4"
  bool square = false;  // marker: square instead of circle
  std::vector<ChartPoint> points;
};

struct Chart {
  std::string title, x_title, y_title;
  std::vector<std::string> notes;  // lines under the title
  std::vector<ChartSeries> series;
};

// Throws InvalidInput when a coordinate is not positive and finite.
std::string render_svg(const Chart& chart);

}  // namespace bssrdf
