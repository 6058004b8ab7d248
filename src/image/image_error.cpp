#include "bssrdf/image/image_error.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "bssrdf/error.hpp"

namespace bssrdf {
namespace {

// Area of the disc of radius r (centred at 0) where X > s.
double area_beyond(double r, double s) {
  if (s <= -r) return std::numbers::pi * r * r;
  if (s >= r) return 0;
  return r * r * std::acos(s / r) - s * std::sqrt(r * r - s * s);
}

// An antiderivative of area_beyond in s (d/ds area_beyond = -2 sqrt(r^2 - s^2), the chord).
double area_beyond_integral(double r, double s) {
  const double h = std::max(0.0, r * r - s * s);
  return s * area_beyond(r, s) - 2.0 / 3.0 * h * std::sqrt(h);
}

}  // namespace

double srgb_encode(double linear) {
  const double v = std::clamp(linear, 0.0, 1.0);
  return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
}

double srgb_slope(double linear) {
  const double v = std::clamp(linear, 0.0, 1.0);
  return v <= 0.0031308 ? 12.92 : 1.055 / 2.4 * std::pow(v, 1 / 2.4 - 1);
}

ImageErrorMeter::ImageErrorMeter(std::vector<double> edges, double pixel) : edges_(std::move(edges)), pixel_(pixel) {
  if (!(pixel > 0) || !std::isfinite(pixel))
    throw InvalidInput("pixel size", format_number(pixel), "> 0 mm and finite");
  if (edges_.size() < 2 || edges_.front() != 0)
    throw InvalidInput("annulus edges", std::to_string(edges_.size()), "0 = r_0 < r_1 < ...");
  const double extent = edges_.back();
  K_ = std::clamp<std::size_t>(static_cast<std::size_t>(std::ceil(extent / pixel)) + 1, 2, kMaxPixelsEachSide);
  // The exitance at x of the edge pattern is sum_i R_i [A(r_{i+1}, -x) - A(r_i, -x)] (the light of
  // annulus i centred at x that falls on X' > 0); its average over the pixel [a, b] is
  // [P(r, -a) - P(r, -b)] / p per radius.
  const std::size_t n = edges_.size();
  std::vector<double> previous(n), current(n);  // P(r_j, -a) at the pixel's left boundary, then right
  const auto boundary = [&](long k, std::vector<double>& out) {
    const double s = -static_cast<double>(k) * pixel_;
    for (std::size_t j = 0; j < n; ++j) out[j] = area_beyond_integral(edges_[j], s);
  };
  const long K = static_cast<long>(K_);
  boundary(-K, previous);
  weight_.assign(2 * K_, {});
  first_.assign(2 * K_, 0);
  for (long k = -K; k < K; ++k) {
    boundary(k + 1, current);
    const auto index = static_cast<std::size_t>(k + K);
    // Annuli no wider than the pixel's distance to the edge lie wholly on its side: weight 1 on the
    // lit side, 0 on the dark one. Only the rest are stored (about 20 a pixel instead of hundreds).
    const double distance = k >= 0 ? static_cast<double>(k) * pixel_ : -static_cast<double>(k + 1) * pixel_;
    std::size_t first = 0;
    while (first + 1 < n && edges_[first + 1] <= distance) ++first;
    first_[index] = first;
    auto& w = weight_[index];
    for (std::size_t i = first; i + 1 < n; ++i) {
      const double outer = (previous[i + 1] - current[i + 1]) / pixel_, inner = (previous[i] - current[i]) / pixel_;
      const double area = std::numbers::pi * (edges_[i + 1] * edges_[i + 1] - edges_[i] * edges_[i]);
      w.push_back(std::clamp((outer - inner) / area, 0.0, 1.0));  // a fraction; clamping only removes rounding
    }
    std::swap(previous, current);
  }
}

double ImageErrorMeter::weight(std::size_t k, std::size_t i) const {
  if (i >= first_[k]) return weight_[k][i - first_[k]];
  return pixel_centre(k) > 0 ? 1.0 : 0.0;
}

double ImageErrorMeter::pixel_centre(std::size_t index) const {
  return (static_cast<double>(index) - static_cast<double>(K_) + 0.5) * pixel_;
}

PatternImage ImageErrorMeter::render(const AnnularProfile& profile) const {
  if (profile.edges != edges_)
    throw InvalidInput("profile annuli", std::to_string(profile.edges.size()), "the meter's annuli");
  PatternImage image;
  const std::size_t pixels = weight_.size();
  image.edge.resize(pixels);
  image.edge_stderr.resize(pixels);
  image.line.resize(pixels);
  image.line_stderr.resize(pixels);
  image.flat = profile.total();
  // Energies of the annuli before each index, for the lit pixels' trivially lit annuli.
  std::vector<double> lit(profile.energy.size() + 1, 0.0), lit_var(profile.energy.size() + 1, 0.0);
  for (std::size_t i = 0; i < profile.energy.size(); ++i) {
    lit[i + 1] = lit[i] + profile.energy[i];
    lit_var[i + 1] = lit_var[i] + profile.energy_stderr[i] * profile.energy_stderr[i];
  }
  for (std::size_t k = 0; k < pixels; ++k) {
    const bool lit_side = pixel_centre(k) > 0;
    double v = lit_side ? lit[first_[k]] : 0, var = lit_side ? lit_var[first_[k]] : 0, line_var = 0;
    for (std::size_t i = first_[k]; i < profile.energy.size(); ++i) {
      const double w = weight_[k][i - first_[k]];
      v += w * profile.energy[i];
      var += w * w * profile.energy_stderr[i] * profile.energy_stderr[i];
    }
    // The line pattern is the edge minus the edge shifted one pixel: weights w_k - w_{k-1}, which
    // vanish where both are trivially equal.
    const std::size_t from = k > 0 ? std::min(first_[k], first_[k - 1]) : 0;
    for (std::size_t i = from; i < profile.energy.size(); ++i) {
      const double dw = weight(k, i) - (k > 0 ? weight(k - 1, i) : 0.0);
      line_var += dw * dw * profile.energy_stderr[i] * profile.energy_stderr[i];
    }
    image.edge[k] = v;
    image.edge_stderr[k] = std::sqrt(var);
    image.line_stderr[k] = std::sqrt(line_var);
  }
  // The shifted edge at pixel k is the edge at pixel k - 1 (0 beyond the dark end).
  for (std::size_t k = 0; k < pixels; ++k) image.line[k] = image.edge[k] - (k > 0 ? image.edge[k - 1] : 0.0);
  return image;
}

PatternImage ImageErrorMeter::render_taps(const std::vector<double>& offset, const std::vector<double>& weight,
                                          double albedo) const {
  if (offset.size() != weight.size())
    throw InvalidInput("kernel taps", std::to_string(weight.size()) + " weights",
                       std::to_string(offset.size()) + " (one per offset)");
  const std::size_t pixels = weight_.size();
  PatternImage image;
  image.flat = albedo;
  image.edge.resize(pixels);
  image.line.resize(pixels);
  image.edge_stderr.assign(pixels, 0.0);
  image.line_stderr.assign(pixels, 0.0);
  // Irradiance of the edge pattern at x (pixel boundaries on the edge: pixel k >= 0 lit), read
  // linearly between pixel centres: 0 up to -p/2, a ramp to 1 at +p/2, 1 beyond. With the taps
  // sorted, a pixel's sum is the weight of the taps past the ramp plus the ramp's taps, from
  // prefix sums of w and w o (two binary searches a pixel).
  std::vector<std::size_t> order(offset.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return offset[a] < offset[b]; });
  std::vector<double> o, W{0.0}, WO{0.0};
  for (std::size_t i : order) {
    o.push_back(offset[i]);
    W.push_back(W.back() + weight[i]);
    WO.push_back(WO.back() + weight[i] * offset[i]);
  }
  const double half = pixel_ / 2;
  for (std::size_t k = 0; k < pixels; ++k) {
    const double x = pixel_centre(k);
    // Beyond the kernel's reach every tap reads the same side.
    if (o.empty() || x + o.front() >= half || x + o.back() <= -half) {
      image.edge[k] = o.empty() || x + o.back() <= -half ? 0.0 : albedo * W.back();
      continue;
    }
    // Taps with x + o <= -p/2 read 0; with x + o >= p/2 read 1; between, (x + o) / p + 1/2.
    const auto lo = static_cast<std::size_t>(std::upper_bound(o.begin(), o.end(), -half - x) - o.begin());
    const auto hi = static_cast<std::size_t>(std::lower_bound(o.begin(), o.end(), half - x) - o.begin());
    const double ramp = (x / pixel_ + 0.5) * (W[hi] - W[lo]) + (WO[hi] - WO[lo]) / pixel_;
    image.edge[k] = albedo * std::clamp(W.back() - W[hi] + ramp, 0.0, W.back());
  }
  for (std::size_t k = 0; k < pixels; ++k) image.line[k] = image.edge[k] - (k > 0 ? image.edge[k - 1] : 0.0);
  return image;
}

ImageError ImageErrorMeter::error(const std::vector<AnnularProfile>& reference,
                                  const std::vector<AnnularProfile>& candidate) const {
  if (reference.size() != candidate.size())
    throw InvalidInput("candidate channels", std::to_string(candidate.size()),
                       std::to_string(reference.size()) + " (the reference's)");
  std::vector<PatternImage> ref, cand;
  for (const auto& p : reference) ref.push_back(render(p));
  for (const auto& p : candidate) cand.push_back(render(p));
  return error(ref, cand);
}

ImageError ImageErrorMeter::error(const std::vector<PatternImage>& reference,
                                  const std::vector<PatternImage>& candidate) const {
  if (reference.size() != candidate.size())
    throw InvalidInput("candidate channels", std::to_string(candidate.size()),
                       std::to_string(reference.size()) + " (the reference's)");
  ImageError result;
  result.error = -1;
  for (std::size_t c = 0; c < reference.size(); ++c) {
    const PatternImage &ref = reference[c], &cand = candidate[c];
    const auto compare = [&](const std::vector<double>& a, const std::vector<double>& a_err,
                             const std::vector<double>& b, const char* name) {
      // sRGB's slope is largest (12.92) at black, so 255 x 12.92 x a linear difference bounds the
      // code difference: pixels whose bound cannot raise the maximum skip the two pow()s.
      constexpr double kMaxCodeSlope = 255 * 12.92;
      for (std::size_t k = 0; k < a.size(); ++k) {
        const double linear = std::abs(a[k] - b[k]);
        result.linear_error = std::max(result.linear_error, linear);
        if (kMaxCodeSlope * a_err[k] > result.reference_noise)
          result.reference_noise = std::max(result.reference_noise, 255 * srgb_slope(a[k]) * a_err[k]);
        if (kMaxCodeSlope * linear <= result.error) continue;
        const double d = 255 * std::abs(srgb_encode(a[k]) - srgb_encode(b[k]));
        if (d > result.error) {
          result.error = d;
          result.pattern = name;
          result.channel = c;
          result.position = pixel_centre(k);
        }
      }
    };
    // A flat lit region shows the diffuse reflectance itself (the albedo), however far the image
    // window reaches.
    compare({ref.flat}, {0.0}, {cand.flat}, "flat");
    compare(ref.edge, ref.edge_stderr, cand.edge, "edge");
    compare(ref.line, ref.line_stderr, cand.line, "line");
  }
  return result;
}

}  // namespace bssrdf
