// The `exact` model's face as a Model (models/exact.hpp): physical units in, the table's transport
// units inside. Profiles are built once per medium and kept per thread, since callers evaluate
// many radii of one medium in a row.
#include <array>
#include <cmath>
#include <optional>

#include "bssrdf/model.hpp"
#include "bssrdf/models/exact.hpp"

namespace bssrdf {

namespace {

class ExactModel final : public Model {
 public:
  std::string name() const override { return "exact"; }
  std::string description() const override {
    return "Radiative-transfer solution, tabulated: project Monte Carlo (multiple scattering), exact single "
           "scattering and adding-doubling totals for a semi-infinite HG medium, interpolated";
  }
  bool includes_single_scattering() const override { return true; }

  double reflectance(const Reduced<double>& m, double r) const override {
    const double s = m.sigma_t_prime;
    return s * s * profile(m).reflectance(r * s);
  }
  double total_reflectance(const Reduced<double>& m) const override {
    return exact_total(bundled_exact_table(), m.albedo_prime, m.g, m.eta);
  }
  double cumulative_reflectance(const Reduced<double>& m, double r) const override {
    return profile(m).cumulative(r * m.sigma_t_prime);
  }
  // Its own inversion: the table covers alpha' 0.001-0.9999 and continues beyond (models/exact.hpp).
  double albedo_prime_from_total(double total, double eta, double g) const override {
    return exact_albedo_prime_from_total(bundled_exact_table(), total, g, eta);
  }

 protected:
  ValidityReport check_validity(const Reduced<double>& m) const override {
    ValidityReport report = exact_domain(bundled_exact_table(), m.albedo_prime, m.g, m.eta);
    if (report.empty())
      report.push_back({Severity::note, "singular_at_origin",
                        "R(r) diverges as 1/r at the entry point (single scattering); its integral is finite"});
    return report;
  }

 private:
  // A few profiles per thread: table builders evaluate their channels interleaved on each thread,
  // and a profile costs 5 to 11 us to build, the time of a hundred evaluations.
  static const ExactProfile& profile(const Reduced<double>& m) {
    struct Cached {
      double albedo_prime = -1, g = -1, eta = -1;
      std::optional<ExactProfile> profile;
    };
    constexpr std::size_t kKept = 4;
    thread_local std::array<Cached, kKept> cache;
    thread_local std::size_t next = 0;
    for (auto& c : cache)
      if (c.profile && c.albedo_prime == m.albedo_prime && c.g == m.g && c.eta == m.eta) return *c.profile;
    Cached& c = cache[next];
    next = (next + 1) % kKept;
    c.profile.emplace(bundled_exact_table(), m.albedo_prime, m.g, m.eta);
    c.albedo_prime = m.albedo_prime;
    c.g = m.g;
    c.eta = m.eta;
    return *c.profile;
  }
};

}  // namespace

std::unique_ptr<Model> make_exact_model() { return std::make_unique<ExactModel>(); }

}  // namespace bssrdf
