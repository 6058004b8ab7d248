#include "bssrdf/advise/validity_map.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "../model_error_table.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/model_choice.hpp"

namespace bssrdf {
namespace {

constexpr double kCell = 22, kPanelGap = 46, kMargin = 70;

// Colour of a relative error on a log scale from 0.3 % (green) to 100 % (red).
std::string error_colour(double e) {
  const double t = std::clamp((std::log10(std::max(e, 1e-6)) - std::log10(0.003)) / (0 - std::log10(0.003)), 0.0, 1.0);
  const int r = static_cast<int>(std::lround(40 + 215 * t)), g = static_cast<int>(std::lround(200 - 170 * t)), b = 60;
  char buffer[8];
  std::snprintf(buffer, sizeof buffer, "#%02x%02x%02x", r, g, b);
  return buffer;
}

const char* kCategorical[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};

// Position of v on an axis of grid values drawn one cell each: piecewise linear between centres.
double axis_position(const std::vector<double>& grid, double v) {
  if (v <= grid.front()) return 0.5 - std::min(0.5, (grid.front() - v) / (grid.front() + 1e-12) * 2);
  for (std::size_t i = 0; i + 1 < grid.size(); ++i)
    if (v <= grid[i + 1]) return 0.5 + static_cast<double>(i) + (v - grid[i]) / (grid[i + 1] - grid[i]);
  return static_cast<double>(grid.size()) - 0.5;
}

}  // namespace

std::string render_validity_map(const ValidityMapOptions& options, const std::vector<Material>& materials) {
  if (options.over != "albedo,eta" && options.over != "albedo,g") throw InvalidInput("--over", options.over, "albedo,eta or albedo,g");
  if (options.metric != "total" && options.metric != "profile")
    throw InvalidInput("--metric", options.metric, "total or profile (image: not measured over the plane yet)");
  if (!(options.tolerance > 0) || !std::isfinite(options.tolerance)) throw InvalidInput("--tolerance", format_number(options.tolerance), "> 0");
  const bool over_eta = options.over == "albedo,eta";
  const std::vector<double> albedo{0.5, 0.8, 0.9, 0.95, 0.99, 0.999};
  const std::vector<double> second = over_eta ? std::vector<double>{1, 1.3, 1.4, 1.5} : std::vector<double>{0, 0.9, 0.95};
  const double fixed = over_eta ? 0.0 : 1.3;  // g on the albedo,eta plane; eta on the albedo,g plane

  // error[model][i][j], i: albedo, j: second axis; NaN where no case was measured.
  const std::size_t models = detail::kCandidateModels;
  std::vector<std::vector<std::vector<double>>> error(models, std::vector<std::vector<double>>(albedo.size(), std::vector<double>(second.size(), NAN)));
  for (const auto& c : detail::kMeasuredCases) {
    if ((over_eta ? c.g : c.eta) != fixed) continue;
    const auto i = std::find(albedo.begin(), albedo.end(), c.albedo_prime) - albedo.begin();
    const auto j = std::find(second.begin(), second.end(), over_eta ? c.eta : c.g) - second.begin();
    if (i >= static_cast<long>(albedo.size()) || j >= static_cast<long>(second.size())) continue;
    for (std::size_t m = 0; m < models; ++m)
      error[m][static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = options.metric == "total" ? c.error[m].total : c.error[m].profile;
  }
  // Models cheapest first, as the choice ranks them.
  std::vector<std::pair<double, std::size_t>> order;
  const auto measured = measured_models();
  for (std::size_t m = 0; m < models; ++m)
    for (const auto& mm : measured)
      if (mm.model == detail::kCandidateNames[m]) order.emplace_back(mm.cost_ns, m);
  std::stable_sort(order.begin(), order.end());

  const double panel_w = kCell * static_cast<double>(albedo.size()), panel_h = kCell * static_cast<double>(second.size());
  const int columns = 4, panels = static_cast<int>(models) + 1, rows = (panels + columns - 1) / columns;
  const double width = kMargin + columns * (panel_w + kPanelGap + 40) + 260, height = 90 + rows * (panel_h + kPanelGap + 40) + 60;
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" font-family=\"sans-serif\" font-size=\"10\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg << "<text x=\"" << kMargin << "\" y=\"22\" font-size=\"15\">Where each model holds: " << options.metric
      << " error against Monte Carlo over alpha' and " << (over_eta ? "eta (g = 0)" : "g (eta = 1.3)") << "</text>\n";
  svg << "<text x=\"" << kMargin << "\" y=\"40\">one cell per measured case (tools/validation/models_vs_montecarlo_extended.tsv, "
         "Monte Carlo noise ~1.5 %); dots: the database's material channels (alpha', "
      << (over_eta ? "eta" : "g") << "); left of 0.5: off the map</text>\n";

  const auto panel = [&](int index, const std::string& title, const auto& cell_colour, const auto& cell_text) {
    const double x0 = kMargin + (index % columns) * (panel_w + kPanelGap + 40), y0 = 70 + (index / columns) * (panel_h + kPanelGap + 40);
    svg << "<text x=\"" << x0 << "\" y=\"" << y0 - 6 << "\" font-size=\"12\">" << title << "</text>\n";
    for (std::size_t i = 0; i < albedo.size(); ++i)
      for (std::size_t j = 0; j < second.size(); ++j) {
        const double x = x0 + kCell * static_cast<double>(i), y = y0 + panel_h - kCell * static_cast<double>(j + 1);
        svg << "<rect x=\"" << x << "\" y=\"" << y << "\" width=\"" << kCell << "\" height=\"" << kCell << "\" fill=\""
            << cell_colour(i, j) << "\" stroke=\"white\"/>";
        const std::string text = cell_text(i, j);
        if (!text.empty())
          svg << "<text x=\"" << x + kCell / 2 << "\" y=\"" << y + kCell / 2 + 3 << "\" text-anchor=\"middle\" font-size=\"8\">" << text
              << "</text>";
        svg << "\n";
      }
    for (std::size_t i = 0; i < albedo.size(); ++i)
      svg << "<text x=\"" << x0 + kCell * (static_cast<double>(i) + 0.5) << "\" y=\"" << y0 + panel_h + 11
          << "\" text-anchor=\"middle\" font-size=\"8\">" << format_number(albedo[i]) << "</text>\n";
    for (std::size_t j = 0; j < second.size(); ++j)
      svg << "<text x=\"" << x0 - 3 << "\" y=\"" << y0 + panel_h - kCell * (static_cast<double>(j) + 0.5) + 3
          << "\" text-anchor=\"end\" font-size=\"8\">" << format_number(second[j]) << "</text>\n";
    svg << "<text x=\"" << x0 + panel_w / 2 << "\" y=\"" << y0 + panel_h + 24 << "\" text-anchor=\"middle\">alpha' (reduced albedo)</text>\n";
    svg << "<text x=\"" << x0 - 26 << "\" y=\"" << y0 + panel_h / 2 << "\" text-anchor=\"middle\" transform=\"rotate(-90 " << x0 - 26
        << " " << y0 + panel_h / 2 << ")\">" << (over_eta ? "eta" : "g") << "</text>\n";
    for (const auto& material : materials)
      for (std::size_t c = 0; c < material.medium.channels(); ++c) {
        const auto m = material.medium.reduced(c);
        const double v = over_eta ? m.eta : m.g;
        svg << "<circle cx=\"" << x0 + kCell * axis_position(albedo, m.albedo_prime) << "\" cy=\""
            << y0 + panel_h - kCell * axis_position(second, v) << "\" r=\"1.6\" fill=\"black\" fill-opacity=\"0.6\"/>\n";
      }
  };
  int index = 0;
  for (const auto& entry : order) {
    const auto m = entry.second;  // a plain variable: C++20 lambdas cannot capture a structured binding in clang 14
    panel(index++, std::string(detail::kCandidateNames[m]), [&](std::size_t i, std::size_t j) { return std::isnan(error[m][i][j]) ? std::string("#dddddd") : error_colour(error[m][i][j]); },
          [&](std::size_t i, std::size_t j) {
            return std::isnan(error[m][i][j]) ? std::string() : std::to_string(static_cast<int>(std::lround(100 * error[m][i][j])));
          });
  }
  // The cheapest model within the tolerance at each measured point.
  const auto cheapest = [&](std::size_t i, std::size_t j) -> int {
    for (std::size_t k = 0; k < order.size(); ++k)
      if (error[order[k].second][i][j] <= options.tolerance) return static_cast<int>(k);
    return -1;
  };
  panel(index, "cheapest within " + format_number(100 * options.tolerance) + " %",
        [&](std::size_t i, std::size_t j) { const int k = cheapest(i, j); return k < 0 ? std::string("#ffffff") : std::string(kCategorical[k]); },
        [&](std::size_t i, std::size_t j) { return cheapest(i, j) < 0 ? std::string("none") : std::string(); });
  // Legends: the error scale and the models' colours.
  const double lx = width - 240;
  svg << "<text x=\"" << lx << "\" y=\"70\" font-size=\"12\">error (cell text: %)</text>\n";
  for (double e : {0.003, 0.01, 0.03, 0.1, 0.3, 1.0}) {
    const double y = 78 + 18 * std::log10(e / 0.003) / std::log10(3.333) * 1.0;
    svg << "<rect x=\"" << lx << "\" y=\"" << y << "\" width=\"14\" height=\"14\" fill=\"" << error_colour(e) << "\"/><text x=\"" << lx + 20
        << "\" y=\"" << y + 11 << "\">" << format_number(100 * e) << " %</text>\n";
  }
  svg << "<text x=\"" << lx << "\" y=\"210\" font-size=\"12\">cheapest within " << format_number(100 * options.tolerance) << " %</text>\n";
  for (std::size_t k = 0; k < order.size(); ++k)
    svg << "<rect x=\"" << lx << "\" y=\"" << 218 + 18 * static_cast<double>(k) << "\" width=\"14\" height=\"14\" fill=\"" << kCategorical[k]
        << "\"/><text x=\"" << lx + 20 << "\" y=\"" << 229 + 18 * static_cast<double>(k) << "\">" << detail::kCandidateNames[order[k].second]
        << " (" << format_number(order[k].first) << " ns)</text>\n";
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace bssrdf
