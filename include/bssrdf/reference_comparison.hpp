// A model's R(r) against a Monte Carlo run's radial tallies (one channel, per entered flux): the
// model averaged over each bin (from cumulative_reflectance) against the bin's tally, the squared
// differences weighted by the bin's area and taken relative to the tallies' own norm, over all
// bins, over the bins inside one transport mean free path (outer edge <= ell: the near field) and
// over the rest (far); with the run's noise measured the same way, and the total's relative error.
// The figures validate_models tabulates and --model auto (model_choice.hpp) relies on.
//
//   const auto run = run_monte_carlo(LayerStack::half_space(medium), options);  // log bins
//   const auto d = compare_with_monte_carlo(*make_model("pbd"), medium.reduced(0), run);
#pragma once

#include <cstddef>

#include "bssrdf/model.hpp"
#include "bssrdf/montecarlo.hpp"

namespace bssrdf {

struct ProfileDeviation {
  double total = 0;                                    // model total / Monte Carlo diffuse reflectance - 1
  double l2 = 0, near = 0, far = 0;                    // relative L2 errors of R(r)
  double l2_noise = 0, near_noise = 0, far_noise = 0;  // the run's own, on the same bins
  // The same with the squared differences of r R(r) over dr (bin width times its representative
  // radius squared): the far field counts more, as it does in a rendered image's halo.
  double near_r = 0, far_r = 0, near_r_noise = 0, far_r_noise = 0;
};

// The model's mean R(r) over the annulus inner < r < outer (from its cumulative reflectance): what a
// Monte Carlo bin tallies.
double model_bin_average(const Model& model, const Reduced<double>& m, double inner, double outer);

ProfileDeviation compare_with_monte_carlo(const Model& model, const Reduced<double>& m, const MonteCarloResult& run,
                                          std::size_t channel = 0);

}  // namespace bssrdf
