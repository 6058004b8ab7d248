// Picking a model by accuracy and cost instead of by habit: the cheapest model whose measured error
// against the Monte Carlo reference meets a stated accuracy at the medium's coefficients.
//
// The errors come from tools/validation/models_vs_montecarlo_extended.tsv (validate_models: 72
// cases, alpha' 0.5-0.999 x eta 1, 1.3, 1.4, 1.5 x g 0, 0.9, 0.95, 2M photons each, Monte Carlo
// noise about 1.5 % in L2), embedded in the library. At given coefficients a model's error is the worst over the
// measured cases that bracket them in alpha', eta and g (not interpolated: conservative); alpha'
// above 0.999 uses the 0.999 cases. Its cost is one R(r) evaluation measured by bench_models.
// Outside the measured ranges there is no estimate and no choice.
//
//   auto choice = choose_model(skin, 0.05);   // throws InvalidInput when no model meets 5 %
//   auto model = make_model(choice.model);
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "bssrdf/medium.hpp"
#include "bssrdf/reduced.hpp"

namespace bssrdf {

struct ModelErrorEstimate {
  std::string model;
  double cost_ns = 0;        // one R(r) evaluation (bench_models median, alpha' 0.9, eta 1.3)
  double total_error = 0;    // |relative error of the total reflectance|
  double profile_error = 0;  // area-weighted relative L2 error of R(r), single scattering included
  // The model's own verdict here: its first "invalid" validity note ("code: message"), empty when it
  // has none. An invalid model is never chosen, whatever its measured error.
  std::string invalid;
  double error() const { return total_error > profile_error ? total_error : profile_error; }
};

// Every candidate model, cheapest first, with its estimated errors at these coefficients;
// nullopt outside the measured ranges (alpha' < 0.5, eta outside [1, 1.5], g outside [0, 0.95]).
std::optional<std::vector<ModelErrorEstimate>> estimate_model_errors(const Reduced<double>& m);

// The same for a medium: the worst over its channels, cheapest first. Throws InvalidInput naming
// the channel and the ranges when a channel is outside them.
std::vector<ModelErrorEstimate> estimate_model_errors(const Medium& medium);

// Every candidate with its cost and its errors in all measured cases (the validation table, in its
// row order), cheapest first: what a speed-against-accuracy chart shows.
struct MeasuredModel {
  std::string model;
  double cost_ns = 0;
  std::vector<double> total_error, profile_error;
};
std::vector<MeasuredModel> measured_models();

// The cheapest valid one of `estimates` (cheapest first) whose error() <= accuracy; nullopt when none is.
std::optional<std::string> cheapest_within(const std::vector<ModelErrorEstimate>& estimates, double accuracy);

struct ModelChoice {
  std::string model;                          // the cheapest whose error() <= accuracy in every channel
  std::vector<ModelErrorEstimate> estimates;  // worst over the channels, cheapest first
};

// Throws InvalidInput as estimate_model_errors(medium) does, or naming the most accurate model and
// its error when none meets `accuracy`.
ModelChoice choose_model(const Medium& medium, double accuracy);

}  // namespace bssrdf
