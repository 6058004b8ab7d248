// The total diffuse reflectance per entered flux of a semi-infinite medium (Henyey-Greenstein phase
// function, smooth boundary of relative index eta, normal incidence) by radiative transfer, not by
// diffusion: the exact model's table inside its domain (models/exact.hpp; within 0.6 % of fresh
// Monte Carlo), adding-doubling outside it (Prahl, Keijzer, Jacques & Welch 1989), and 1 without
// absorption (all light that enters a non-absorbing half-space leaves it again).
//
//   const auto t = transport_total(reduce(0.01, 10.0, 0.9, 1.4));
//   if (t.reliable()) use(t.value);
//
// Adding-doubling uses the delta-M approximation, which does not converge at g near 1 with little
// scattering (it even gives negative totals at alpha' 0.001, g 0.99): its own error estimate is
// returned, and reliable() says whether it is below 1e-3 of the total.
#pragma once

#include "bssrdf/reduced.hpp"

namespace bssrdf {

struct TransportTotal {
  double value = 0;
  const char* source = "";    // "exact", "adding-doubling", "no absorption" or "no scattering"
  double error_estimate = 0;  // adding-doubling's own (0 for the others)
  bool reliable() const { return value >= 0 && error_estimate <= 1e-3 * value + 1e-9; }
};

TransportTotal transport_total(const Reduced<double>& m);

}  // namespace bssrdf
