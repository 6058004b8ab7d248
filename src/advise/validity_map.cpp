#include "bssrdf/advise/validity_map.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "../io/canvas.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/image/image_error.hpp"
#include "bssrdf/model_choice.hpp"
#include "bssrdf/model_registry.hpp"

namespace bssrdf {
namespace {

constexpr double kCell = 22, kPanelGap = 46, kMargin = 70;

// Colour of an error on a log scale from lo (green) to hi (red).
std::string error_colour(double e, double lo, double hi) {
  const double t =
      std::clamp((std::log10(std::max(e, 1e-12)) - std::log10(lo)) / (std::log10(hi) - std::log10(lo)), 0.0, 1.0);
  const int r = static_cast<int>(std::lround(40 + 215 * t)), g = static_cast<int>(std::lround(200 - 170 * t)), b = 60;
  char buffer[8];
  std::snprintf(buffer, sizeof buffer, "#%02x%02x%02x", r, g, b);
  return buffer;
}

const char* kCategorical[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                              "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};

// Position of v on an axis of grid values drawn one cell each: piecewise linear between centres.
double axis_position(const std::vector<double>& grid, double v) {
  if (v <= grid.front()) return 0.5 - std::min(0.5, (grid.front() - v) / (grid.front() + 1e-12) * 2);
  for (std::size_t i = 0; i + 1 < grid.size(); ++i)
    if (v <= grid[i + 1]) return 0.5 + static_cast<double>(i) + (v - grid[i]) / (grid[i + 1] - grid[i]);
  return static_cast<double>(grid.size()) - 0.5;
}

}  // namespace

std::string render_validity_map(const ValidityMapOptions& options, const std::vector<Material>& materials,
                                const ReferenceProfile* reference) {
  if (options.over != "albedo,eta" && options.over != "albedo,g")
    throw InvalidInput("--over", options.over, "albedo,eta or albedo,g");
  if (options.metric != "total" && options.metric != "profile" && options.metric != "image")
    throw InvalidInput("--metric", options.metric, "total, profile or image");
  if (!(options.tolerance > 0) || !std::isfinite(options.tolerance))
    throw InvalidInput("--tolerance", format_number(options.tolerance), "> 0");
  if (!(options.pixel > 0) || !std::isfinite(options.pixel) || options.pixel > 1e4)
    throw InvalidInput("--pixel", format_number(options.pixel), "> 0 and <= 10000 transport mean free paths");
  const bool image = options.metric == "image";
  if (image && !reference)
    throw InvalidInput("--metric", "image", "total or profile (image needs a reference profile)");
  const bool over_eta = options.over == "albedo,eta";
  const double fixed = over_eta ? 0.0 : 1.3;  // g on the albedo,eta plane; eta on the albedo,g plane
  // total/profile: measured live against the exact model on a dense grid inside its domain; image:
  // one reference run per cell on a coarse grid (each cell costs a reference).
  const std::vector<double> albedo = image
                                         ? std::vector<double>{0.5, 0.8, 0.9, 0.95, 0.99, 0.999}
                                         : std::vector<double>{0.3, 0.5, 0.7, 0.8, 0.9, 0.95, 0.98, 0.99, 0.995, 0.999};
  const std::vector<double> second =
      over_eta
          ? (image ? std::vector<double>{1, 1.3, 1.4, 1.5} : std::vector<double>{1, 1.1, 1.2, 1.3, 1.4, 1.5, 1.6})
          : (image ? std::vector<double>{0, 0.9, 0.95} : std::vector<double>{0, 0.3, 0.5, 0.7, 0.8, 0.9, 0.95, 0.99});

  // The models drawn: every --model auto candidate but the reference itself, with their costs.
  std::vector<std::string> names;
  for (const auto& entry : model_registry())
    if (entry.auto_candidate && !entry.reference_accuracy) names.push_back(entry.name);
  const std::size_t models = names.size();
  // error[model][i][j], i: albedo, j: second axis; NaN where nothing was measured.
  std::vector<std::vector<std::vector<double>>> error(
      models, std::vector<std::vector<double>>(albedo.size(), std::vector<double>(second.size(), NAN)));
  std::string source;
  for (std::size_t i = 0; i < albedo.size(); ++i)
    for (std::size_t j = 0; j < second.size(); ++j) {
      const double g = over_eta ? fixed : second[j], eta = over_eta ? second[j] : fixed;
      const Medium medium = Medium::single_channel(1 - albedo[i], albedo[i] / (1 - g), g, eta);
      const auto m = medium.reduced(0);
      if (image) {
        // sigma_t' = 1/mm: the reference once, every model judged on its annuli.
        const ReferenceProfiles ref = reference->profiles(medium);
        if (source.empty()) source = "the reference at each cell, " + ref.description;
        const ImageErrorMeter meter(ref.channels.front().edges, options.pixel);
        const std::vector<PatternImage> ref_image{meter.render(ref.channels.front())};
        for (std::size_t k = 0; k < models; ++k) {
          const auto model = make_model(names[k]);
          const auto profile = annuli_of(
              meter.edges(), [&](double r) { return model->reflectance(m, r); }, model->total_reflectance(m));
          error[k][i][j] = meter.error(ref_image, {meter.render(profile)}).error;
        }
      } else if (const auto estimates = model_errors_vs_exact(m)) {
        for (const auto& e : *estimates) {
          const auto k = std::find(names.begin(), names.end(), e.model) - names.begin();
          if (k < static_cast<long>(models))
            error[static_cast<std::size_t>(k)][i][j] = options.metric == "total" ? e.total_error : e.profile_error;
        }
      }
    }
  if (!image) {
    const auto band = *model_entry("exact").reference_accuracy;
    source = "measured live (the exact model itself is within " + format_number(std::round(1000 * band.total) / 10) +
             " % in total and " + format_number(std::round(1000 * band.profile) / 10) +
             " % in profile of Monte Carlo); profile: relative L2 of r R(r), the worse of inside and beyond one "
             "transport mfp";
  }
  // The colour scale and cell text: percent for relative errors, code values for the image.
  const double lo = image ? 0.1 : 0.003, hi = image ? 100 : 1;
  const auto cell_value = [&](double e) {
    return image
               ? (e < 9.95 ? format_number(std::round(e * 10) / 10) : std::to_string(static_cast<int>(std::lround(e))))
               : std::to_string(static_cast<int>(std::lround(100 * e)));
  };
  const std::string tolerance_text =
      image ? format_number(options.tolerance) + " code values" : format_number(100 * options.tolerance) + " %";
  // Models cheapest first, as the choice ranks them.
  std::vector<std::pair<double, std::size_t>> order;
  for (std::size_t m = 0; m < models; ++m) order.emplace_back(model_entry(names[m]).cost_ns, m);
  std::stable_sort(order.begin(), order.end());

  const double panel_w = kCell * static_cast<double>(albedo.size()),
               panel_h = kCell * static_cast<double>(second.size());
  const int columns = 4, panels = static_cast<int>(models) + 1, rows = (panels + columns - 1) / columns;
  const double width = kMargin + columns * (panel_w + kPanelGap + 40) + 260,
               height = 90 + rows * (panel_h + kPanelGap + 40) + 60;
  auto canvas = make_canvas(options.extension, width, height);
  const std::string what = image ? "image error (8-bit sRGB code values, shadow edge and one-pixel line, pixel " +
                                       format_number(options.pixel) + " transport mfp)"
                                 : options.metric + " error";
  canvas->text(kMargin, 22,
               "Where each model holds: " + what + " against " + (image ? "the reference" : "the exact model") +
                   " over alpha' and " + (over_eta ? "eta (g = 0)" : "g (eta = 1.3)"),
               15);
  canvas->text(kMargin, 38, "one cell per point: " + source, 10);
  canvas->text(kMargin, 51,
               "dots: the database's material channels (alpha', " + std::string(over_eta ? "eta" : "g") +
                   "); left of " + format_number(albedo.front()) + ": off the map",
               10);

  const auto panel = [&](int index, const std::string& title, const auto& cell_colour, const auto& cell_text) {
    const double x0 = kMargin + (index % columns) * (panel_w + kPanelGap + 40),
                 y0 = 70 + (index / columns) * (panel_h + kPanelGap + 40);
    canvas->text(x0, y0 - 6, title, 12);
    for (std::size_t i = 0; i < albedo.size(); ++i)
      for (std::size_t j = 0; j < second.size(); ++j) {
        const double x = x0 + kCell * static_cast<double>(i), y = y0 + panel_h - kCell * static_cast<double>(j + 1);
        canvas->rect(x, y, kCell, kCell, cell_colour(i, j), true);
        const std::string text = cell_text(i, j);
        if (!text.empty()) canvas->text(x + kCell / 2, y + kCell / 2 + 3, text, 8, Anchor::middle);
      }
    for (std::size_t i = 0; i < albedo.size(); ++i)
      canvas->text(x0 + kCell * (static_cast<double>(i) + 0.5), y0 + panel_h + 11, format_number(albedo[i]), 8,
                   Anchor::middle);
    for (std::size_t j = 0; j < second.size(); ++j)
      canvas->text(x0 - 3, y0 + panel_h - kCell * (static_cast<double>(j) + 0.5) + 3, format_number(second[j]), 8,
                   Anchor::end);
    canvas->text(x0 + panel_w / 2, y0 + panel_h + 24, "alpha' (reduced albedo)", 10, Anchor::middle);
    canvas->text(x0 - 3, y0 + 2, over_eta ? "eta" : "g", 9, Anchor::end);  // the second axis, above its ticks
    for (const auto& material : materials)
      for (std::size_t c = 0; c < material.medium.channels(); ++c) {
        const auto m = material.medium.reduced(c);
        const double v = over_eta ? m.eta : m.g;
        canvas->disc(x0 + kCell * axis_position(albedo, m.albedo_prime),
                     y0 + panel_h - kCell * axis_position(second, v), 1.6, "#000000", 0.6);
      }
  };
  int index = 0;
  for (const auto& entry : order) {
    const auto m = entry.second;  // a plain variable: C++20 lambdas cannot capture a structured binding in clang 14
    panel(
        index++, names[m],
        [&](std::size_t i, std::size_t j) {
          return std::isnan(error[m][i][j]) ? std::string("#dddddd") : error_colour(error[m][i][j], lo, hi);
        },
        [&](std::size_t i, std::size_t j) {
          return std::isnan(error[m][i][j]) ? std::string() : cell_value(error[m][i][j]);
        });
  }
  // The cheapest model within the tolerance at each point.
  const auto cheapest = [&](std::size_t i, std::size_t j) -> int {
    for (std::size_t k = 0; k < order.size(); ++k)
      if (error[order[k].second][i][j] <= options.tolerance) return static_cast<int>(k);
    return -1;
  };
  panel(
      index, "cheapest within " + tolerance_text,
      [&](std::size_t i, std::size_t j) {
        const int k = cheapest(i, j);
        return k < 0 ? std::string("#ffffff") : std::string(kCategorical[k]);
      },
      [&](std::size_t i, std::size_t j) { return cheapest(i, j) < 0 ? std::string("none") : std::string(); });
  // Legends: the error scale and the models' colours.
  const double lx = width - 240;
  canvas->text(lx, 70, image ? "error (cell text: code values)" : "error (cell text: %)", 12);
  for (int step = 0; step <= 6; ++step) {
    const double e = lo * std::pow(hi / lo, step / 6.0), y = 78 + 18 * step;
    canvas->rect(lx, y, 14, 14, error_colour(e, lo, hi));
    canvas->text(lx + 20, y + 11,
                 image ? format_number(std::round(e * 100) / 100) : format_number(std::round(1000 * e) / 10) + " %",
                 10);
  }
  canvas->text(lx, 226, "cheapest within " + tolerance_text, 12);
  for (std::size_t k = 0; k < order.size(); ++k) {
    canvas->rect(lx, 234 + 18 * static_cast<double>(k), 14, 14, kCategorical[k]);
    canvas->text(lx + 20, 245 + 18 * static_cast<double>(k),
                 names[order[k].second] + " (" + format_number(order[k].first) + " ns)", 10);
  }
  canvas->rect(lx, 234 + 18 * static_cast<double>(order.size()), 14, 14, "#dddddd");
  canvas->text(lx + 20, 245 + 18 * static_cast<double>(order.size()), "not measured; white: none within", 10);
  return canvas->encode();
}

}  // namespace bssrdf
