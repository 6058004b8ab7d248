#include "bssrdf/io/svg_chart.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "bssrdf/error.hpp"
#include "xml_escape.hpp"

namespace bssrdf {
namespace {

constexpr double kWidth = 820, kHeight = 520, kLeft = 80, kRight = 190, kTop = 70, kBottom = 60;

std::string number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f", v);
  return buffer;
}

std::string decade_label(int e) {
  if (e >= 0 && e <= 5) return std::to_string(static_cast<long>(std::pow(10.0, e)));
  if (e < 0 && e >= -3) {
    char buffer[16];
    std::snprintf(buffer, sizeof buffer, "%.*f", -e, std::pow(10.0, e));
    return buffer;
  }
  return "1e" + std::to_string(e);
}

struct LogAxis {
  int lo, hi;       // decades
  double from, to;  // pixels
  double at(double v) const { return from + (std::log10(v) - lo) / (hi - lo) * (to - from); }
};

}  // namespace

std::string render_svg(const Chart& chart) {
  double x_min = INFINITY, x_max = 0, y_min = INFINITY, y_max = 0;
  for (const auto& s : chart.series)
    for (const auto& p : s.points) {
      for (double v : {p.x, p.y})
        if (!(v > 0) || !std::isfinite(v))
          throw InvalidInput("chart point " + p.label, std::to_string(v), "> 0 and finite (log axes)");
      x_min = std::min(x_min, p.x), x_max = std::max(x_max, p.x);
      y_min = std::min({y_min, p.y, p.y_low > 0 ? p.y_low : p.y}), y_max = std::max({y_max, p.y, p.y_high});
    }
  if (!(x_max > 0)) throw InvalidInput("chart: no points");
  // Room beside the last points for their labels, and above the highest.
  const LogAxis X{static_cast<int>(std::floor(std::log10(x_min))), static_cast<int>(std::ceil(std::log10(x_max * 3))),
                  kLeft, kWidth - kRight};
  const LogAxis Y{static_cast<int>(std::floor(std::log10(y_min))), static_cast<int>(std::ceil(std::log10(y_max * 1.5))),
                  kHeight - kBottom, kTop};
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << kHeight
      << "\" viewBox=\"0 0 " << kWidth << ' ' << kHeight << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << kLeft << "\" y=\"24\" font-size=\"16\" font-weight=\"bold\">" << xml_escape(chart.title)
      << "</text>\n";
  for (std::size_t i = 0; i < chart.notes.size(); ++i)
    svg << "<text x=\"" << kLeft << "\" y=\"" << 42 + 14 * i << "\" font-size=\"11\" fill=\"#555\">"
        << xml_escape(chart.notes[i]) << "</text>\n";
  // Grid: decades solid, 2 and 5 dotted; labels at decades.
  for (int e = X.lo; e <= X.hi; ++e)
    for (int m : {1, 2, 5}) {
      const double v = m * std::pow(10.0, e);
      if (e == X.hi && m > 1) break;
      const std::string x = number(X.at(v));
      svg << "<line x1=\"" << x << "\" y1=\"" << number(Y.from) << "\" x2=\"" << x << "\" y2=\"" << number(Y.to)
          << "\" stroke=\"#" << (m == 1 ? "ccc" : "eee") << "\"/>\n";
      if (m == 1)
        svg << "<text x=\"" << x << "\" y=\"" << number(Y.from + 18) << "\" text-anchor=\"middle\">" << decade_label(e)
            << "</text>\n";
    }
  for (int e = Y.lo; e <= Y.hi; ++e)
    for (int m : {1, 2, 5}) {
      const double v = m * std::pow(10.0, e);
      if (e == Y.hi && m > 1) break;
      const std::string y = number(Y.at(v));
      svg << "<line x1=\"" << number(X.from) << "\" y1=\"" << y << "\" x2=\"" << number(X.to) << "\" y2=\"" << y
          << "\" stroke=\"#" << (m == 1 ? "ccc" : "eee") << "\"/>\n";
      if (m == 1)
        svg << "<text x=\"" << number(X.from - 8) << "\" y=\"" << number(Y.at(v) + 4) << "\" text-anchor=\"end\">"
            << decade_label(e) << "</text>\n";
    }
  svg << "<rect x=\"" << kLeft << "\" y=\"" << kTop << "\" width=\"" << number(X.to - X.from) << "\" height=\""
      << number(Y.from - Y.to) << "\" fill=\"none\" stroke=\"#333\"/>\n"
      << "<text x=\"" << number(0.5 * (X.from + X.to)) << "\" y=\"" << number(kHeight - 16)
      << "\" text-anchor=\"middle\">" << xml_escape(chart.x_title) << "</text>\n"
      << "<text transform=\"translate(20 " << number(0.5 * (Y.from + Y.to)) << ") rotate(-90)\" text-anchor=\"middle\">"
      << xml_escape(chart.y_title) << "</text>\n";
  // Labels beside their points: right, else left, else a line lower on the right, and so on, at the
  // first place that overlaps no earlier label or marker.
  struct Box {
    double x0, y0, x1, y1;
  };
  std::vector<Box> placed;
  for (const auto& s : chart.series)
    for (const auto& p : s.points) placed.push_back({X.at(p.x) - 5, Y.at(p.y) - 5, X.at(p.x) + 5, Y.at(p.y) + 5});
  const auto place = [&](double x, double y, const std::string& text) {
    const double w = 6.6 * static_cast<double>(text.size());
    const auto clear = [&](const Box& b) {
      return std::none_of(placed.begin(), placed.end(),
                          [&](const Box& o) { return b.x0 < o.x1 && o.x0 < b.x1 && b.y0 < o.y1 && o.y0 < b.y1; });
    };
    Box chosen{x + 8, y - 8, x + 8 + w, y + 5};
    for (int line = 0; line < 12; ++line) {
      const double dy = 13.0 * (line % 2 ? -(line + 1) / 2 : line / 2);
      const Box right{x + 8, y - 8 + dy, x + 8 + w, y + 5 + dy}, left{x - 8 - w, y - 8 + dy, x - 8, y + 5 + dy};
      if (clear(right)) {
        chosen = right;
        break;
      }
      if (left.x0 > kLeft && clear(left)) {
        chosen = left;
        break;
      }
    }
    placed.push_back(chosen);
    return std::pair{chosen.x0, chosen.y1 - 1};
  };
  for (const auto& s : chart.series)
    for (const auto& p : s.points) {
      const double x = X.at(p.x), y = Y.at(p.y);
      if (p.y_low > 0 && p.y_high > 0)
        svg << "<line x1=\"" << number(x) << "\" y1=\"" << number(Y.at(p.y_low)) << "\" x2=\"" << number(x)
            << "\" y2=\"" << number(Y.at(p.y_high)) << "\" stroke=\"" << s.colour << "\" stroke-opacity=\"0.6\"/>\n";
      if (s.square)
        svg << "<rect x=\"" << number(x - 4) << "\" y=\"" << number(y - 4) << "\" width=\"8\" height=\"8\" fill=\""
            << s.colour << "\"/>\n";
      else
        svg << "<circle cx=\"" << number(x) << "\" cy=\"" << number(y) << "\" r=\"4.5\" fill=\"" << s.colour
            << "\"/>\n";
      if (!p.label.empty()) {
        const auto [lx, ly] = place(x, y, p.label);
        if (std::abs(ly - 5 - y) > 6) {  // moved away from its point: a leader line back to it
          const double edge = lx > x ? lx - 2 : lx + 6.6 * static_cast<double>(p.label.size()) + 2;
          svg << "<line x1=\"" << number(x) << "\" y1=\"" << number(y) << "\" x2=\"" << number(edge) << "\" y2=\""
              << number(ly - 5) << "\" stroke=\"#999\" stroke-width=\"0.7\"/>\n";
        }
        svg << "<text x=\"" << number(lx) << "\" y=\"" << number(ly) << "\" fill=\"#222\">" << xml_escape(p.label)
            << "</text>\n";
      }
    }
  // Legend, right of the plot.
  for (std::size_t i = 0; i < chart.series.size(); ++i) {
    const auto& s = chart.series[i];
    const double y = kTop + 10 + 18 * static_cast<double>(i), x = kWidth - kRight + 14;
    svg << (s.square
                ? "<rect x=\"" + number(x - 4) + "\" y=\"" + number(y - 4) + "\" width=\"8\" height=\"8\" fill=\"" +
                      s.colour + "\"/>\n"
                : "<circle cx=\"" + number(x) + "\" cy=\"" + number(y) + "\" r=\"4.5\" fill=\"" + s.colour + "\"/>\n")
        << "<text x=\"" << number(x + 10) << "\" y=\"" << number(y + 4) << "\" font-size=\"11\">" << xml_escape(s.name)
        << "</text>\n";
  }
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace bssrdf
