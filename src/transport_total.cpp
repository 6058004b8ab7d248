#include "bssrdf/transport_total.hpp"

#include "bssrdf/adding_doubling/slab.hpp"
#include "bssrdf/models/exact.hpp"

namespace bssrdf {

TransportTotal transport_total(const Reduced<double>& m) {
  if (!(m.sigma_s > 0)) return {0.0, "no scattering", 0.0};
  if (m.sigma_a == 0) return {1.0, "no absorption", 0.0};
  const ExactTable& table = bundled_exact_table();
  if (exact_domain(table, m.albedo_prime, m.g, m.eta).empty())
    return {exact_total(table, m.albedo_prime, m.g, m.eta), "exact", 0.0};
  const auto t = adding_doubling::solve(adding_doubling::half_space(m), adding_doubling::Incidence::collimated);
  // The quadrature can overshoot 1 by its error estimate near alpha' = 1.
  const double total = t.diffuse_reflectance * t.entered_scale();
  return {total > 1 && total - 1 <= t.error_estimate ? 1.0 : total, "adding-doubling", t.error_estimate};
}

}  // namespace bssrdf
