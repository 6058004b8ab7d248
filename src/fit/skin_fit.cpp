#include "bssrdf/fit/skin_fit.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bssrdf/error.hpp"
#include "bssrdf/skin/chromophores.hpp"
#include "fit_common.hpp"

namespace bssrdf {
namespace {

// The fitted parameters, in the order of the solver's vector.
struct Fitted {
  const char* name;
  double skin::SkinParameters::*member;
  double min, max;  // the solver's bounds: within the model's ranges, off the degenerate ends
  const char* unit;
};
const std::vector<Fitted>& spectrum_parameters() {
  using P = skin::SkinParameters;
  static const std::vector<Fitted> list = {
      {"melanin", &P::melanin, 1e-4, 0.6, ""},
      {"eumelanin", &P::eumelanin, 0, 1, ""},
      {"blood", &P::blood, 1e-4, 0.3, ""},
      {"oxygenation", &P::oxygenation, 0, 1, ""},
      {"epidermis", &P::epidermis_mm, 0.01, 0.5, "mm"},
      {"scattering", &P::scattering_500, 0.1, 20, "1/mm"},
      {"scattering_power", &P::scattering_power, 0, 4, ""},
  };
  return list;
}
const std::vector<Fitted>& colour_parameters() {
  using P = skin::SkinParameters;
  static const std::vector<Fitted> list = {{"melanin", &P::melanin, 1e-4, 0.6, ""},
                                           {"eumelanin", &P::eumelanin, 0, 1, ""},
                                           {"blood", &P::blood, 1e-4, 0.3, ""}};
  return list;
}

skin::SkinParameters with(const skin::SkinParameters& base, const std::vector<Fitted>& list, const double* x) {
  auto p = base;
  // Clamped: the solver's finite-difference steps may cross a bound.
  for (std::size_t i = 0; i < list.size(); ++i) p.*list[i].member = std::clamp(x[i], list[i].min, list[i].max);
  return p;
}

// Model reflectance at `nm` for parameters x.
struct SpectrumResidual {
  const skin::SkinParameters* base;
  const std::vector<double>* nm;
  const std::vector<double>* measured;
  bool specular;
  int points;
  int* evaluations;
  bool operator()(double const* const* x, double* residual) const {
    ++*evaluations;
    const auto r = skin::skin_reflectance(with(*base, spectrum_parameters(), x[0]), *nm, points).total(specular);
    for (std::size_t i = 0; i < r.size(); ++i) residual[i] = r[i] - (*measured)[i];
    return true;
  }
};

struct ColourResidual {
  const skin::SkinParameters* base;
  const spectral::ColourIntegrator* colour;
  spectral::Vec3 target_lab;
  bool specular;
  int points;
  int* evaluations;
  bool operator()(double const* const* x, double* residual) const {
    ++*evaluations;
    const auto r =
        skin::skin_reflectance(with(*base, colour_parameters(), x[0]), colour->wavelengths(), points).total(specular);
    const auto lab = colour->lab(r);
    for (int k = 0; k < 3; ++k) residual[k] = lab[k] - target_lab[k];
    return true;
  }
};

struct Solved {
  std::vector<double> x;
  std::vector<double> stderr_;
  std::string status;
  int iterations = 0;
};

// Start values on a coarse grid: the fits are not convex (a thin, dark epidermis and a thick, light one can both
// explain a spectrum locally), so Levenberg-Marquardt starts from the grid point of least cost. `grid`: for some of
// the fitted parameters (by name), the values tried; the others stay at `start`.
template <class Functor>
std::vector<double> grid_start(const Functor& functor, int residuals, const std::vector<Fitted>& list,
                               const skin::SkinParameters& start,
                               const std::vector<std::pair<std::string, std::vector<double>>>& grid) {
  std::vector<double> x, best;
  for (const auto& f : list) x.push_back(std::clamp(start.*f.member, f.min, f.max));
  std::vector<std::size_t> index_of;
  for (const auto& g : grid)
    for (std::size_t i = 0; i < list.size(); ++i)
      if (g.first == list[i].name) index_of.push_back(i);
  std::vector<double> r(residuals);
  double best_cost = std::numeric_limits<double>::infinity();
  std::vector<std::size_t> at(grid.size(), 0);
  while (true) {
    for (std::size_t k = 0; k < grid.size(); ++k) x[index_of[k]] = grid[k].second[at[k]];
    const double* block = x.data();
    functor(&block, r.data());
    double cost = 0;
    for (double v : r) cost += v * v;
    if (cost < best_cost) best_cost = cost, best = x;
    std::size_t k = 0;
    while (k < grid.size() && ++at[k] == grid[k].second.size()) at[k++] = 0;
    if (k == grid.size()) break;
  }
  return best;
}

template <class Functor>
Solved solve(Functor functor, int residuals, const std::vector<Fitted>& list, std::vector<double> start) {
  Solved out;
  out.x = std::move(start);
  const int n = static_cast<int>(list.size());
  auto* cost = new ceres::DynamicNumericDiffCostFunction<Functor, ceres::FORWARD>(new Functor(functor));
  cost->AddParameterBlock(n);
  cost->SetNumResiduals(residuals);
  ceres::Problem problem;
  problem.AddResidualBlock(cost, nullptr, out.x.data());
  for (int i = 0; i < n; ++i) {
    problem.SetParameterLowerBound(out.x.data(), i, list[i].min);
    problem.SetParameterUpperBound(out.x.data(), i, list[i].max);
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 100;
  options.function_tolerance = 1e-8;
  options.parameter_tolerance = 1e-10;
  options.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  out.iterations = static_cast<int>(summary.iterations.size());
  out.status = summary.termination_type == ceres::CONVERGENCE ? "converged"
               : summary.IsSolutionUsable()                   ? "no_convergence"
                                                              : "failed";
  out.stderr_.assign(n, std::numeric_limits<double>::quiet_NaN());
  if (residuals > n) {
    if (const auto cov = parameter_covariance(problem, {out.x.data()})) {
      const double variance = 2 * summary.final_cost / (residuals - n);
      for (int i = 0; i < n; ++i) out.stderr_[i] = std::sqrt((*cov)(i, i) * variance);
    }
  }
  return out;
}

double cpu_now() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

void report_parameters(SkinFitResult& result, const std::vector<Fitted>& list, const Solved& solved) {
  for (std::size_t i = 0; i < list.size(); ++i)
    result.reported.push_back({list[i].name, list[i].unit, solved.x[i], solved.stderr_[i],
                               solved.x[i] <= list[i].min || solved.x[i] >= list[i].max});
  result.status = solved.status;
  result.iterations = solved.iterations;
}

}  // namespace

SkinFitResult fit_skin_spectrum(const ReflectanceSpectrum& spectrum, const SkinFitOptions& options) {
  options.start.validate();
  const double cpu0 = cpu_now();
  const auto wall0 = std::chrono::steady_clock::now();
  SkinFitResult result;
  result.source = spectrum.file + " (" + spectrum.column + ")";
  result.specular_included = options.specular_included;
  const double lo = std::max(options.min_nm, skin::kChromophoreMinNm),
               hi = std::min(options.max_nm, skin::kChromophoreMaxNm);
  std::vector<double> solve_nm, solve_measured;
  for (std::size_t i = 0; i < spectrum.wavelength_nm.size(); ++i) {
    const double nm = spectrum.wavelength_nm[i];
    if (nm < lo || nm > hi) continue;
    result.wavelength_nm.push_back(nm);
    result.measured.push_back(spectrum.reflectance[i]);
    if (solve_nm.empty() || nm - solve_nm.back() >= options.solve_step_nm - 1e-9)
      solve_nm.push_back(nm), solve_measured.push_back(spectrum.reflectance[i]);
  }
  const auto& list = spectrum_parameters();
  if (solve_nm.size() <= list.size())
    throw InvalidInput("spectrum",
                       std::to_string(result.wavelength_nm.size()) + " wavelengths within " + format_number(lo) + "-" +
                           format_number(hi) + " nm",
                       "more than " + std::to_string(list.size()) + " (one per fitted parameter)");
  SpectrumResidual functor{&options.start,  &solve_nm,
                           &solve_measured, options.specular_included,
                           options.points,  &result.residual_evaluations};
  const int residuals = static_cast<int>(solve_nm.size());
  const auto start = grid_start(
      functor, residuals, list, options.start,
      {{"melanin", {0.002, 0.01, 0.03, 0.08, 0.2}}, {"scattering", {1.5, 3, 6, 12}}, {"epidermis", {0.05, 0.2}}});
  const auto solved = solve(functor, residuals, list, start);
  report_parameters(result, list, solved);
  result.parameters = with(options.start, list, solved.x.data());
  result.fitted =
      skin::skin_reflectance(result.parameters, result.wavelength_nm, options.points).total(options.specular_included);
  double sum = 0;
  for (std::size_t i = 0; i < result.fitted.size(); ++i) sum += std::pow(result.fitted[i] - result.measured[i], 2);
  result.rms = std::sqrt(sum / result.fitted.size());
  const spectral::ColourIntegrator colour(result.wavelength_nm, {});
  result.delta_e2000 = spectral::ciede2000(colour.lab(result.measured), colour.lab(result.fitted));
  result.cpu_seconds = cpu_now() - cpu0;
  result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return result;
}

SkinFitResult fit_skin_colour(const spectral::Vec3& linear_srgb, const SkinFitOptions& options) {
  options.start.validate();
  for (double v : linear_srgb)
    if (!(v > 0 && v < 1)) throw InvalidInput("srgb", format_number(v), "0 < value < 1 (linear)");
  const double cpu0 = cpu_now();
  const auto wall0 = std::chrono::steady_clock::now();
  SkinFitResult result;
  result.specular_included = options.specular_included;
  std::vector<double> nm;
  for (double l = 380; l <= 780; l += 10) nm.push_back(l);
  const spectral::ColourIntegrator colour(nm, {});
  const auto white = spectral::white_xyz(spectral::Illuminant::d65);
  const auto to_xyz = spectral::inverse(spectral::xyz_to_rgb_matrix(spectral::ColourSpace::srgb, white));
  using spectral::operator*;
  const auto target_lab = spectral::xyz_to_lab(to_xyz * linear_srgb, white);
  ColourResidual functor{
      &options.start, &colour, target_lab, options.specular_included, options.points, &result.residual_evaluations};
  const auto& list = colour_parameters();
  const auto start = grid_start(functor, 3, list, options.start,
                                {{"melanin", {0.002, 0.01, 0.03, 0.08, 0.2, 0.4}}, {"blood", {0.005, 0.02, 0.06}}});
  const auto solved = solve(functor, 3, list, start);
  report_parameters(result, list, solved);
  result.parameters = with(options.start, list, solved.x.data());
  result.wavelength_nm = nm;
  result.fitted = skin::skin_reflectance(result.parameters, nm, options.points).total(options.specular_included);
  result.delta_e2000 = spectral::ciede2000(target_lab, colour.lab(result.fitted));
  result.rms = std::numeric_limits<double>::quiet_NaN();
  result.cpu_seconds = cpu_now() - cpu0;
  result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return result;
}

std::string SkinFitResult::to_json() const {
  nlohmann::json doc;
  doc["source"] = source;
  doc["model"] = "two-layer skin (epidermis with melanin over a semi-infinite dermis with blood), adding-doubling";
  doc["specular_included"] = specular_included;
  doc["wavelength_nm"] = wavelength_nm;
  doc["measured"] = measured;
  doc["fitted"] = fitted;
  doc["rms"] = std::isfinite(rms) ? nlohmann::json(rms) : nlohmann::json(nullptr);
  doc["delta_e2000"] = delta_e2000;
  doc["parameters"] = nlohmann::json::object();
  for (const auto& p : reported)
    doc["parameters"][p.name] = {
        {"value", p.value},
        {"stderr", std::isfinite(p.stderr_) ? nlohmann::json(p.stderr_) : nlohmann::json(nullptr)},
        {"unit", p.unit},
        {"at_bound", p.at_bound}};
  doc["fixed"] = {{"water", parameters.water}, {"g", parameters.g}, {"eta", parameters.eta}};
  doc["status"] = status;
  doc["iterations"] = iterations;
  doc["residual_evaluations"] = residual_evaluations;
  doc["cpu_seconds"] = cpu_seconds;
  doc["wall_seconds"] = wall_seconds;
  return doc.dump(2) + "\n";
}

std::string SkinFitResult::to_table() const {
  std::ostringstream out;
  out << "fit skin  " << source << " (" << (specular_included ? "specular included" : "specular excluded") << ")\n";
  out << "status    " << status << " after " << iterations << " iterations, " << residual_evaluations
      << " model spectra, " << format_number(std::round(cpu_seconds * 1000) / 1000) << " s CPU\n";
  for (const auto& p : reported)
    out << "  " << p.name << std::string(18 - std::min<std::size_t>(17, p.name.size()), ' ')
        << format_number(std::round(p.value * 1e5) / 1e5) << " +- "
        << (std::isfinite(p.stderr_) ? format_number(std::round(p.stderr_ * 1e5) / 1e5) : std::string("?")) << " "
        << p.unit << (p.at_bound ? "  (at a bound of its range)" : "") << "\n";
  if (std::isfinite(rms)) out << "rms       " << format_number(std::round(rms * 1e5) / 1e5) << " (reflectance)\n";
  out << "dE2000    " << format_number(std::round(delta_e2000 * 1000) / 1000) << " (D65)\n";
  return out.str();
}

}  // namespace bssrdf
