// A model's error measured live against the exact model (models/exact.hpp) at one medium, for
// `--model auto` (model_choice.hpp) inside the exact table's domain.
#pragma once

#include "bssrdf/model.hpp"
#include "bssrdf/models/exact.hpp"
#include "bssrdf/reduced.hpp"

namespace bssrdf::detail {

// The exact profile's bins: 64 log-spaced bins from 1e-3 transport mfp to the radius holding
// 99.9 % of its energy (at least 2 mfp), split at 1 mfp, with its bin averages of r R(r) over dr
// and its total.
struct ExactBins {
  std::vector<double> edges;    // 65 radii, transport mfp
  std::vector<double> average;  // 64 bin averages of r R(r), transport units
  double total = 0;
};
ExactBins exact_bins(const ExactProfile& exact);

struct ErrorVsExact {
  double total = 0;  // |model total / exact total - 1|
  double near = 0;   // relative L2 of the bin averages of r R(r) over dr, bins inside one transport mfp
  double far = 0;    // the same beyond it
  double profile() const { return near > far ? near : far; }  // the far field counts as much
};
// `model` at `m` against the exact bins of the same medium (lengths scaled by m.ell).
ErrorVsExact error_vs_exact(const Model& model, const Reduced<double>& m, const ExactBins& exact);

}  // namespace bssrdf::detail
