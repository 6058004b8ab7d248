// Totals of a slab by adding-doubling: layers, boundaries, incidence; angles chosen from the
// tolerance. See include/bssrdf/adding_doubling/slab.hpp.
#include "bssrdf/adding_doubling/slab.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <map>

#include "angles.hpp"
#include "boundary.hpp"
#include "bssrdf/error.hpp"
#include "layer_modes.hpp"
#include "layer_operator.hpp"

namespace bssrdf::adding_doubling {

std::string_view to_string(Incidence incidence) {
  return incidence == Incidence::collimated ? "collimated" : "diffuse";
}

Incidence parse_incidence(const std::string& text) {
  if (text == "collimated") return Incidence::collimated;
  if (text == "diffuse") return Incidence::diffuse;
  throw InvalidInput("incidence", text, "collimated or diffuse");
}

void Slab::validate() const {
  auto finite_positive = [](double v) { return v > 0 && std::isfinite(v); };
  if (layers.empty()) throw InvalidInput("layers", "none", "at least one scattering layer");
  if (!finite_positive(n)) throw InvalidInput("n", format_number(n), "> 0 and finite");
  if (!finite_positive(ambient_above))
    throw InvalidInput("ambient_above", format_number(ambient_above), "> 0 and finite");
  if (!finite_positive(ambient_below))
    throw InvalidInput("ambient_below", format_number(ambient_below), "> 0 and finite");
  for (std::size_t k = 0; k < layers.size(); ++k) {
    const auto& l = layers[k];
    const std::string f = "layers[" + std::to_string(k) + "].";
    if (!(l.sigma_a >= 0 && std::isfinite(l.sigma_a)))
      throw InvalidInput(f + "sigma_a", format_number(l.sigma_a), ">= 0 and finite");
    if (!(l.sigma_s >= 0 && std::isfinite(l.sigma_s)))
      throw InvalidInput(f + "sigma_s", format_number(l.sigma_s), ">= 0 and finite");
    if (!(l.g > -1 && l.g < 1)) throw InvalidInput(f + "g", format_number(l.g), "-1 < g < 1");
    const bool last = k + 1 == layers.size();
    if (!(finite_positive(l.thickness) || (last && l.thickness == kSemiInfinite)))
      throw InvalidInput(f + "thickness", format_number(l.thickness),
                         last ? "> 0 (or semi-infinite)" : "> 0 and finite");
    if (last && l.thickness == kSemiInfinite && !(l.sigma_a + l.sigma_s > 0))
      throw InvalidInput(f + "sigma_t", "0", "> 0 for a semi-infinite layer");
  }
  for (const auto* side : {&above, &below})
    for (std::size_t k = 0; k < side->size(); ++k) {
      const auto& c = (*side)[k];
      const std::string f = std::string(side == &above ? "slides_above[" : "slides_below[") + std::to_string(k) + "].";
      if (!finite_positive(c.n)) throw InvalidInput(f + "n", format_number(c.n), "> 0 and finite");
      if (!finite_positive(c.thickness))
        throw InvalidInput(f + "thickness", format_number(c.thickness), "> 0 and finite");
      if (!(c.sigma_a >= 0 && std::isfinite(c.sigma_a)))
        throw InvalidInput(f + "sigma_a", format_number(c.sigma_a), ">= 0 and finite");
    }
}

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// Critical cosine inside the slab for light to reach a medium of index m.
double critical_cosine(double n, double m) { return m < n ? std::sqrt(1 - (m / n) * (m / n)) : 0.0; }

double min_index(double ambient, const std::vector<ClearLayer>& clear) {
  double m = ambient;
  for (const auto& c : clear) m = std::min(m, c.n);
  return m;
}

// What a slab's solution at `points` angles needs besides the layers' thicknesses: the angles, the
// boundaries and each scattering layer's phase function. Slabs that differ only in thickness share it.
struct Geometry {
  Angles angles;
  std::size_t beam = 0;  // the collimated beam's angle
  Boundary top, bottom;
  std::vector<PhaseBlocks> phase;  // per scattering layer
  // Per scattering layer when its medium is shared too (solve_thicknesses); else empty, and
  // homogeneous_layer finds the modes itself.
  std::vector<LayerModes> modes;
};

double albedo_of(const ScatteringLayer& l) {
  const double sigma_t = l.sigma_a + l.sigma_s;
  return sigma_t > 0 ? l.sigma_s / sigma_t : 0.0;
}

Geometry make_geometry(const Slab& slab, int points, double incidence_cosine) {
  Geometry geo;
  // The beam inside the slab, by Snell's law from the ambient above (the slides do not change it).
  const double sine = slab.ambient_above / slab.n * std::sqrt(1 - incidence_cosine * incidence_cosine);
  const double beam = incidence_cosine == 1 ? 1.0 : std::sqrt(std::max(0.0, 1 - sine * sine));
  geo.angles = make_angles(points,
                           {critical_cosine(slab.n, min_index(slab.ambient_above, slab.above)),
                            critical_cosine(slab.n, min_index(slab.ambient_below, slab.below))},
                           beam);
  geo.beam = node_of(geo.angles, beam);
  // The boundaries, as media from top to bottom with the half-spaces at the ends.
  std::vector<ClearLayer> top{{slab.ambient_above, 0, 0}}, bottom{{slab.n, 0, 0}};
  top.insert(top.end(), slab.above.begin(), slab.above.end());
  top.push_back({slab.n, 0, 0});
  bottom.insert(bottom.end(), slab.below.begin(), slab.below.end());
  bottom.push_back({slab.ambient_below, 0, 0});
  geo.top = make_boundary(geo.angles, slab.n, top);
  geo.bottom = make_boundary(geo.angles, slab.n, bottom);
  for (const auto& l : slab.layers) geo.phase.push_back(phase_blocks(geo.angles, l.g));
  return geo;
}

// make_geometry, remembered per thread for the last slabs seen: an inversion solves the same
// sample (indices, slides, g) at many coefficients, and the angles, boundaries and phase function
// were ~20 % of each solve at 8 angles. The same computation, so results are bitwise the same.
const Geometry& cached_geometry(const Slab& slab, int points, double incidence_cosine) {
  std::vector<double> key{double(points), incidence_cosine, slab.n, slab.ambient_above, slab.ambient_below};
  for (const auto* side : {&slab.above, &slab.below}) {
    key.push_back(double(side->size()));
    for (const auto& c : *side) key.insert(key.end(), {c.n, c.thickness, c.sigma_a});
  }
  for (const auto& l : slab.layers) key.push_back(l.g);
  thread_local std::map<std::vector<double>, Geometry> cache;
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  if (cache.size() >= 16) cache.clear();  // bounded (<= 4 MB at 128 angles): a run over many samples starts afresh
  return cache.emplace(std::move(key), make_geometry(slab, points, incidence_cosine)).first->second;
}

// The scattering layers S between the slab's boundaries: totals for each incidence. Fixed-size
// matrices at the common angle counts (see layer_operator.hpp: Square<N>), dynamic otherwise.
template <int N>
std::vector<Totals> with_boundaries(const Slab& slab, const std::vector<Incidence>& incidences, const Geometry& geo,
                                    const LayerOperator& S, double optical_depth) {
  using Matrix = Square<N>;
  using Vector = Column<N>;
  const Angles& angles = geo.angles;
  const int n = static_cast<int>(angles.size());
  const Boundary& B_top = geo.top;
  const Boundary& B_bottom = geo.bottom;
  // Slab with its bottom boundary: y = (I - R_bottom Rb)^-1 T_down x is the downward flux at the
  // bottom face; R' = R_top + T_up Rb y, T' = Tb y.
  Vector rb(n), tb(n), rt_out(n), rt_in(n), tt(n);
  for (int i = 0; i < n; ++i) {
    rb(i) = B_bottom.r_top[i];
    tb(i) = B_bottom.t[i];
    rt_out(i) = B_top.r_top[i];
    rt_in(i) = B_top.r_bottom[i];
    tt(i) = B_top.t[i];
  }
  const Matrix I = Matrix::Identity(n, n);
  Matrix R1 = S.R_top, T1 = Matrix::Zero(n, n);
  if (!std::isinf(optical_depth)) {
    const Matrix R_bottom = S.R_bottom, T_down = S.T_down, T_up = S.T_up;
    const Matrix Y = (I - R_bottom * rb.asDiagonal()).partialPivLu().solve(T_down);
    R1.noalias() += T_up.lazyProduct(rb.asDiagonal() * Y);
    T1 = tb.asDiagonal() * Y;
  }
  // Downward flux below the top boundary: x = tt f + rt_in R' x (one factorisation for all incidences).
  const Eigen::PartialPivLU<Matrix> inward(I - rt_in.asDiagonal() * R1);
  std::vector<Totals> results;
  for (const auto incidence : incidences) {
    // Incident flux per angle (outside the slab, labelled by the slab angle it refracts into).
    Vector incident = Vector::Zero(n);
    double cannot_enter = 0;  // diffuse light at angles with no counterpart inside (n < ambient)
    if (incidence == Incidence::collimated) {
      incident(static_cast<Eigen::Index>(geo.beam)) = 1;
    } else {
      // Uniform radiance outside: by Snell, n_a^2 nu dnu = n^2 mu dmu, so angle i carries
      // (n/n_a)^2 2 mu_i w_i of the flux where it connects to the outside.
      const double ratio = slab.n / slab.ambient_above;
      double sum = 0;
      for (int i = 0; i < n; ++i) {
        const double s = ratio * std::sqrt(std::max(0.0, 1 - angles.mu[i] * angles.mu[i]));
        if (s < 1) incident(i) = ratio * ratio * 2 * angles.mu[i] * angles.weight[i];
        sum += incident(i);
      }
      cannot_enter = std::max(0.0, 1 - sum);
    }
    // Solved as a vector of run-time size (at most N, no allocation): Eigen's general triangular
    // solver then skips zero entries, so angles that neither receive light nor couple to any
    // (trapped between two total reflections in a clear sample: a zero row and zero source) stay
    // dark instead of 0/0; its unrolled fixed-size solver would divide.
    using Flux = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, N, 1>;
    const Flux x = inward.solve(Flux(tt.cwiseProduct(incident)));
    Totals out;
    out.points = n;
    out.specular_reflectance = rt_out.dot(incident) + cannot_enter;
    out.diffuse_reflectance = tt.dot(R1 * x);
    out.total_transmittance = (T1 * x).sum();
    if (!std::isinf(optical_depth))
      for (int i = 0; i < n; ++i) {
        const double e = std::exp(-optical_depth / angles.mu[i]);
        const double bounce = 1 - rt_in(i) * rb(i) * e * e;
        if (bounce > 0) {
          out.unscattered_transmittance += incident(i) * tt(i) * tb(i) * e / bounce;
          out.unscattered_reflectance += incident(i) * tt(i) * tt(i) * rb(i) * e * e / bounce;
        }
      }
    out.unscattered_reflectance += out.specular_reflectance;
    results.push_back(out);
  }
  return results;
}

std::vector<Totals> solve_with(const Slab& slab, const std::vector<Incidence>& incidences, const Geometry& geo) {
  // The scattering layers, added top to bottom.
  LayerOperator S;
  double optical_depth = 0;  // along the normal, true (not delta-M) coefficients
  for (std::size_t k = 0; k < slab.layers.size(); ++k) {
    const auto& l = slab.layers[k];
    const double sigma_t = l.sigma_a + l.sigma_s;
    const double tau = std::isinf(l.thickness) ? INFINITY : sigma_t * l.thickness;
    const auto layer = homogeneous_layer(geo.angles, albedo_of(l), l.g, tau, &geo.phase[k],
                                         k < geo.modes.size() ? &geo.modes[k] : nullptr);
    S = k == 0 ? layer : add(S, layer);
    optical_depth += tau;
  }
  switch (geo.angles.size()) {
    case 8:
      return with_boundaries<8>(slab, incidences, geo, S, optical_depth);
    case 12:
      return with_boundaries<12>(slab, incidences, geo, S, optical_depth);
    case 16:
      return with_boundaries<16>(slab, incidences, geo, S, optical_depth);
    default:
      return with_boundaries<Eigen::Dynamic>(slab, incidences, geo, S, optical_depth);
  }
}

// The tolerance loop over the number of angles; geometry(points) gives the slab's Geometry.
template <class GeometryOf>
std::vector<Totals> solve_converged(const Slab& slab, const std::vector<Incidence>& incidences, const Options& options,
                                    GeometryOf&& geometry) {
  if (options.points > 0) return solve_with(slab, incidences, geometry(options.points));
  if (!(options.tolerance > 0)) throw InvalidInput("tolerance", format_number(options.tolerance), "> 0");
  // Angles 8, 16, 32, ...: the error of the finest result is estimated from the last two changes
  // (geometric convergence with ratio rho leaves rho/(1 - rho) of the last change), never less
  // than a quarter of the last change, and the last change itself when the changes do not shrink
  // by half. At least three results (32 angles), since one change alone can be small by chance.
  // With several incidences the largest estimate decides for all.
  auto coarse = solve_with(slab, incidences, geometry(8));
  std::vector<double> last_change(2 * incidences.size(), -1);
  for (int points = 16;; points *= 2) {
    auto fine = solve_with(slab, incidences, geometry(points));
    double estimate_all = 0;
    for (std::size_t i = 0; i < incidences.size(); ++i) {
      const double change[2] = {std::abs(fine[i].diffuse_reflectance - coarse[i].diffuse_reflectance),
                                std::abs(fine[i].total_transmittance - coarse[i].total_transmittance)};
      fine[i].error_estimate = 0;
      for (int k = 0; k < 2; ++k) {
        double estimate = change[k];
        double& last = last_change[2 * i + k];
        if (last > 0) {
          const double rho = change[k] / last;
          if (rho < 0.5) estimate = change[k] * std::max(0.25, rho / (1 - rho));
        }
        fine[i].error_estimate = std::max(fine[i].error_estimate, estimate);
        last = change[k];
      }
      estimate_all = std::max(estimate_all, fine[i].error_estimate);
    }
    coarse = fine;
    if ((points >= 32 && estimate_all <= options.tolerance) || points >= 128) return fine;
  }
}

void check_incidence(const Options& options) {
  if (!(options.incidence_cosine > 0 && options.incidence_cosine <= 1))
    throw InvalidInput("incidence cosine", format_number(options.incidence_cosine),
                       "(0, 1] (angle of incidence below 90 degrees)");
}

}  // namespace

std::vector<Totals> solve(const Slab& slab, const std::vector<Incidence>& incidences, const Options& options) {
  slab.validate();
  check_incidence(options);
  return solve_converged(slab, incidences, options, [&](int points) -> const Geometry& {
    return cached_geometry(slab, points, options.incidence_cosine);
  });
}

std::vector<Totals> solve_thicknesses(const Slab& slab, const std::vector<double>& thicknesses, Incidence incidence,
                                      const Options& options) {
  slab.validate();
  check_incidence(options);
  if (slab.layers.size() != 1)
    throw InvalidInput("layers", std::to_string(slab.layers.size()), "1 (one layer whose thickness varies)");
  std::map<int, Geometry> geometries;  // by number of angles, shared by every thickness
  const auto geometry = [&](int points) -> const Geometry& {
    auto it = geometries.find(points);
    if (it == geometries.end()) {
      Geometry geo = make_geometry(slab, points, options.incidence_cosine);
      // The medium's modes too, where homogeneous_layer takes them: one eigen-decomposition for every thickness.
      const auto& l = slab.layers[0];
      geo.modes.push_back(layer_modes(geo.angles, delta_m_albedo(albedo_of(l), l.g, geo.angles.size()), geo.phase[0]));
      it = geometries.emplace(points, std::move(geo)).first;
    }
    return it->second;
  };
  std::vector<Totals> out;
  Slab one = slab;
  for (double d : thicknesses) {
    one.layers[0].thickness = d;
    one.validate();
    out.push_back(solve_converged(one, {incidence}, options, geometry)[0]);
  }
  return out;
}

Totals solve(const Slab& slab, Incidence incidence, const Options& options) {
  return solve(slab, std::vector{incidence}, options)[0];
}

Slab half_space(const Reduced<double>& m) {
  Slab slab;
  slab.layers = {{m.sigma_a, m.sigma_s, m.g, kSemiInfinite}};
  slab.n = m.eta;
  return slab;
}

Slab slab_of(const LayerStack& stack, std::size_t c) {
  stack.validate();
  Slab slab;
  slab.ambient_above = stack.ambient_above;
  slab.ambient_below = stack.ambient_below;
  std::size_t first = 0, last = stack.layers.size();
  while (first < last && stack.layers[first].sigma_s[c] == 0 && std::isfinite(stack.layers[first].thickness)) ++first;
  while (last > first && stack.layers[last - 1].sigma_s[c] == 0 && std::isfinite(stack.layers[last - 1].thickness))
    --last;
  auto clear = [&](const Layer& l) { return ClearLayer{l.n, l.thickness, l.sigma_a[c]}; };
  for (std::size_t k = 0; k < first; ++k) slab.above.push_back(clear(stack.layers[k]));
  for (std::size_t k = last; k < stack.layers.size(); ++k) slab.below.push_back(clear(stack.layers[k]));
  if (first == last)
    throw InvalidInput("layers", "no scattering layer in channel " + stack.channel_names[c], "at least one");
  slab.n = stack.layers[first].n;
  for (std::size_t k = first; k < last; ++k) {
    const auto& l = stack.layers[k];
    const std::string field = "layers[" + std::to_string(k) + "]";
    if (l.n != slab.n)
      throw InvalidInput(field + ".n", format_number(l.n),
                         format_number(slab.n) + " (adding-doubling needs one index for all scattering layers)");
    if (l.sigma_s[c] == 0)
      throw InvalidInput(field + ".sigma_s[" + stack.channel_names[c] + "]", "0",
                         "> 0 (adding-doubling takes non-scattering layers only above or below the scattering ones)");
    slab.layers.push_back({l.sigma_a[c], l.sigma_s[c], l.g[c], l.thickness});
  }
  return slab;
}

}  // namespace bssrdf::adding_doubling
