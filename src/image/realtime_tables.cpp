#include "bssrdf/image/realtime_tables.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "bssrdf/error.hpp"
#include "bssrdf/lut/gaussian_mixture_table.hpp"

namespace bssrdf {

namespace {

// A sum of Gaussians on annuli: the light of one inside radius r is w (1 - exp(-r^2 / 2v)), so
// each annulus's share is exact.
std::vector<AnnularProfile> gaussian_annuli(const GaussianMixtureTable& table, const std::vector<double>& edges) {
  std::vector<AnnularProfile> profiles;
  for (std::size_t c = 0; c < table.weight.size(); ++c) {
    AnnularProfile p{edges, std::vector<double>(edges.size() - 1, 0.0), std::vector<double>(edges.size() - 1, 0.0)};
    const auto& w = table.weight[c];
    const auto& v = table.variance[c];
    for (std::size_t k = 0; k < w.size(); ++k) {
      double inside = 0;
      for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
        const double next = w[k] * -std::expm1(-edges[i + 1] * edges[i + 1] / (2 * v[k]));
        p.energy[i] += next - inside;
        inside = next;
      }
    }
    profiles.push_back(std::move(p));
  }
  return profiles;
}

}  // namespace

RealtimeJudge judge_against(const Medium& medium, const ReferenceProfile& reference, double pixel) {
  const ReferenceProfiles ref = reference.profiles(medium);
  RealtimeJudge judge{ImageErrorMeter(ref.channels.front().edges, pixel), {}, {}};
  for (const auto& p : ref.channels) {
    judge.reference.push_back(judge.meter.render(p));
    judge.albedo.push_back(p.total());
  }
  return judge;
}

ImageError RealtimeJudge::error(const std::vector<AnnularProfile>& candidate) const {
  std::vector<PatternImage> images;
  for (const auto& p : candidate) images.push_back(meter.render(p));
  return meter.error(reference, images);
}

std::vector<PatternImage> render_separable(const ImageErrorMeter& meter, const SeparableKernel& kernel) {
  std::vector<double> offset;
  for (double o : kernel.offset) offset.push_back(o * kernel.options.range);
  std::vector<PatternImage> images;
  for (std::size_t c = 0; c < kernel.weight.size(); ++c)
    images.push_back(meter.render_taps(offset, kernel.weight[c], kernel.total_reflectance[c]));
  return images;
}

SeparableChoice choose_separable_kernel(const Medium& medium,
                                        const std::vector<std::optional<ProjectedProfile>>& profiles,
                                        const RealtimeJudge& judge, double tolerance) {
  // The band's half-width per band, once (each kernel would search it again).
  std::vector<double> range(kSeparableBands.size(), 0.0);
  for (std::size_t b = 0; b < kSeparableBands.size(); ++b)
    for (const auto& p : profiles)
      if (p) range[b] = std::max(range[b], p->line_width_for_fraction(kSeparableBands[b]));
  SeparableChoice best;
  best.image.error = INFINITY;
  for (int taps : kSeparableTaps) {
    SeparableChoice within;
    within.image.error = INFINITY;
    for (std::size_t b = 0; b < kSeparableBands.size(); ++b) {
      SeparableKernelOptions options;
      options.taps = taps;
      options.band = kSeparableBands[b];
      options.range = range[b] > 0 ? range[b] : 1;  // no channel scatters: identity kernels, any range
      const SeparableKernel kernel = build_separable_kernel(medium, profiles, options);
      const ImageError e = judge.error(render_separable(judge.meter, kernel));
      if (e.error < best.image.error) best = {options, e, false};
      if (e.error <= tolerance && e.error < within.image.error) within = {options, e, true};
    }
    if (within.meets_tolerance) return within;
  }
  return best;
}

double preintegrated_table_error(const PreintegratedTable& table, const PreintegratedTable& finer,
                                 const std::vector<double>& albedo) {
  const std::size_t W = table.options.width, H = table.options.height, FW = finer.options.width,
                    FH = finer.options.height;
  // Texel-centre coordinates of the finer table in the coarser one's texel index, clamped (a
  // clamp-to-edge bilinear fetch).
  const auto coordinate = [](double u01, std::size_t n) {
    return std::clamp(u01 * static_cast<double>(n) - 0.5, 0.0, static_cast<double>(n - 1));
  };
  double worst = 0;
  for (std::size_t c = 0; c < table.value.size(); ++c)
    for (std::size_t j = 0; j < FH; ++j) {
      const double y = coordinate((static_cast<double>(j) + 0.5) / static_cast<double>(FH), H);
      const auto j0 = std::min(static_cast<std::size_t>(y), H > 1 ? H - 2 : 0);
      const double ty = H > 1 ? y - static_cast<double>(j0) : 0;
      const std::size_t j1 = H > 1 ? j0 + 1 : 0;
      for (std::size_t i = 0; i < FW; ++i) {
        const double x = coordinate((static_cast<double>(i) + 0.5) / static_cast<double>(FW), W);
        const auto i0 = std::min(static_cast<std::size_t>(x), W - 2);
        const double tx = x - static_cast<double>(i0);
        const auto& v = table.value[c];
        const double bottom = (1 - tx) * v[j0 * W + i0] + tx * v[j0 * W + i0 + 1],
                     top = (1 - tx) * v[j1 * W + i0] + tx * v[j1 * W + i0 + 1];
        const double D = (1 - ty) * bottom + ty * top, exact = finer.value[c][j * FW + i];
        worst = std::max(worst, 255 * std::abs(srgb_encode(albedo[c] * D) - srgb_encode(albedo[c] * exact)));
      }
    }
  return worst;
}

namespace {

// On the flat patterns no light crosses the edge; the lit side shows albedo x the texel a flat,
// fully lit surface reads (N.L = 1 and curvature 0 clamp to the last column of row 0). The error is
// the larger of that image's and the table's interpolation error.
ImageError preintegrated_image(const RealtimeJudge& judge, const PreintegratedTable& table, double table_error) {
  std::vector<AnnularProfile> flat;
  for (std::size_t c = 0; c < judge.albedo.size(); ++c)
    flat.push_back(point_profile(judge.meter.edges(), judge.albedo[c] * table.value[c][table.options.width - 1]));
  ImageError image = judge.error(flat);
  if (table_error > image.error) {
    image.error = table_error;
    image.pattern = "curvature table";
  }
  return image;
}

}  // namespace

PreintegratedChoice choose_preintegrated_table(const Medium& medium,
                                               const std::vector<std::optional<ProjectedProfile>>& profiles,
                                               const RealtimeJudge& judge, double tolerance, bool stop_at_flat_error) {
  const auto build = [&](std::size_t n, double curvature_max) {
    PreintegratedOptions options;
    options.width = options.height = n;
    options.curvature_max = curvature_max;
    return build_preintegrated_table(medium, profiles, options);
  };
  PreintegratedTable table = build(kPreintegratedSizes.front(), 0);
  const double curvature_max = table.options.curvature_max;
  PreintegratedChoice best;
  best.image.error = INFINITY;
  for (std::size_t n : kPreintegratedSizes) {
    PreintegratedTable finer = build(2 * n, curvature_max);
    PreintegratedChoice choice;
    choice.size = n;
    choice.curvature_max = curvature_max;
    choice.table_error = preintegrated_table_error(table, finer, judge.albedo);
    choice.image = preintegrated_image(judge, table, choice.table_error);
    choice.meets_tolerance = choice.image.error <= tolerance;
    // A larger table cannot help once its interpolation is within the tolerance or below the flat
    // patterns' error (which no table size changes: the LUT does not carry light across the edge).
    if (choice.table_error <= (stop_at_flat_error ? std::max(tolerance, choice.image.error) : tolerance) ||
        n == kPreintegratedSizes.back())
      return choice;
    if (choice.image.error < best.image.error) best = choice;
    table = std::move(finer);
  }
  return best;
}

std::vector<AnnularProfile> gaussian_sum_profiles(const Medium& medium, const Model& model, int count,
                                                  const std::vector<double>& edges) {
  return gaussian_annuli(fitted_mixture_table(medium, model, count, kGaussianFitSamples), edges);
}

std::vector<AnnularProfile> radial_table_profiles(const Medium& medium, const Model& model, std::size_t radii,
                                                  const std::vector<double>& edges) {
  std::vector<AnnularProfile> profiles;
  for (std::size_t c = 0; c < medium.channels(); ++c) {
    const auto table = radial_table(model, medium.reduced(c), radii);
    profiles.push_back(annuli_of(edges, table, 0));  // no light beyond the table
  }
  return profiles;
}

namespace {

// stop_early: give up once a size no longer cuts the error by 10 % (for the Gaussian fits, whose
// cost grows fast with the count, and whose error then is the fitted model's own).
template <class Sizes, class Profiles>
CountChoice smallest_within(const Sizes& sizes, const RealtimeJudge& judge, double tolerance, bool stop_early,
                            const Profiles& profiles) {
  CountChoice best;
  best.image.error = INFINITY;
  for (auto n : sizes) {
    const ImageError e = judge.error(profiles(n));
    if (e.error <= tolerance) return {static_cast<std::size_t>(n), e, true};
    if (stop_early && !(e.error < 0.9 * best.image.error)) break;
    if (e.error < best.image.error) best = {static_cast<std::size_t>(n), e, false};
  }
  return best;
}

}  // namespace

CountChoice choose_gaussian_count(const Medium& medium, const Model& model, const RealtimeJudge& judge,
                                  double tolerance) {
  return smallest_within(kGaussianCounts, judge, tolerance, true,
                         [&](int k) { return gaussian_sum_profiles(medium, model, k, judge.meter.edges()); });
}

CountChoice choose_radial_table_size(const Medium& medium, const Model& model, const RealtimeJudge& judge,
                                     double tolerance) {
  return smallest_within(kRadialTableSizes, judge, tolerance, false,
                         [&](std::size_t n) { return radial_table_profiles(medium, model, n, judge.meter.edges()); });
}

ImageError image_error_of(const RealtimeJudge& judge, const SeparableKernel& kernel) {
  return judge.error(render_separable(judge.meter, kernel));
}

ImageError image_error_of(const RealtimeJudge& judge, const GaussianMixtureTable& table) {
  return judge.error(gaussian_annuli(table, judge.meter.edges()));
}

ImageError image_error_of(const RealtimeJudge& judge, const RadialTable& table) {
  std::vector<AnnularProfile> profiles;
  for (std::size_t c = 0; c < table.channel_names.size(); ++c)
    profiles.push_back(annuli_of(
        judge.meter.edges(), [&](double r) { return table.interpolate(c, r); }, 0));
  return judge.error(profiles);
}

ImageError image_error_of(const RealtimeJudge& judge, const PreintegratedTable& table, const Medium& medium,
                          const std::vector<std::optional<ProjectedProfile>>& profiles) {
  PreintegratedOptions finer = table.options;
  finer.width = std::min<std::size_t>(2 * finer.width, 8192);
  finer.height = std::min<std::size_t>(2 * finer.height, 8192);
  return preintegrated_image(
      judge, table, preintegrated_table_error(table, build_preintegrated_table(medium, profiles, finer), judge.albedo));
}

RadialToleranceChoice choose_radial_tolerance(const Medium& medium, const Model& model, const RealtimeJudge& judge,
                                              double tolerance, RadialTableOptions options) {
  RadialToleranceChoice best;
  best.image.error = INFINITY;
  for (double relative : {1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4}) {
    options.tolerance = relative;
    const ImageError e = image_error_of(judge, build_radial_table(medium, model, options));
    if (e.error <= tolerance) return {relative, e, true};
    if (e.error < best.image.error) best = {relative, e, false};
  }
  return best;
}

RadialTableNodes radial_table_nodes(const std::function<double(double)>& reflectance, const Reduced<double>& m,
                                    std::size_t n, double lo_ell, double hi_ell) {
  if (n < 2) throw InvalidInput("radial table radii", std::to_string(n), ">= 2");
  const double lo = lo_ell * m.ell;
  // By default as far as the reference's annuli reach (profile_extent: the light left out is invisible).
  const double hi = hi_ell > 0 ? hi_ell * m.ell : profile_extent(m);
  RadialTableNodes nodes;
  for (std::size_t j = 0; j < n; ++j) {
    nodes.radius.push_back(lo * std::pow(hi / lo, static_cast<double>(j) / static_cast<double>(n - 1)));
    nodes.value.push_back(reflectance(nodes.radius.back()));
  }
  return nodes;
}

RadialTableNodes radial_table_nodes(const Model& model, const Reduced<double>& m, std::size_t n, double lo_ell,
                                    double hi_ell) {
  return radial_table_nodes([&](double r) { return model.reflectance(m, r); }, m, n, lo_ell, hi_ell);
}

std::function<double(double)> radial_table(const RadialTableNodes& nodes) {
  const std::size_t n = nodes.radius.size();
  const double lo = nodes.radius.front(), hi = nodes.radius.back(),
               step = std::log(hi / lo) / static_cast<double>(n - 1);
  std::vector<double> log_R;
  for (double R : nodes.value) log_R.push_back(std::log(std::max(R, 1e-300)));
  return [lo, hi, step, log_R](double r) {
    if (r > hi) return 0.0;
    const double u = std::log(std::max(r, lo) / lo) / step;
    const auto j = std::min(static_cast<std::size_t>(u), log_R.size() - 2);
    const double t = u - static_cast<double>(j);
    return std::exp((1 - t) * log_R[j] + t * log_R[j + 1]);
  };
}

std::function<double(double)> radial_table(const Model& model, const Reduced<double>& m, std::size_t n, double lo_ell,
                                           double hi_ell) {
  return radial_table(radial_table_nodes(model, m, n, lo_ell, hi_ell));
}

}  // namespace bssrdf
