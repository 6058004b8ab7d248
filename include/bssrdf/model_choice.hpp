// Picking a model by accuracy and cost instead of by habit: the cheapest model whose error
// against the reference meets a stated accuracy at the medium's coefficients.
//
// Inside the exact model's domain (models/exact.hpp: alpha' 0.001-0.9999, g 0-0.99, eta 1-1.6)
// every candidate is measured live against `exact` at the medium itself: its total error
// |T / T_exact - 1| and its profile error, the relative L2 of the bin averages of r R(r) over dr
// on 64 log-spaced bins from 1e-3 transport mfp to the exact profile's 99.9 % radius, taken
// separately inside and beyond one transport mfp, the larger of the two (so far-field errors are
// not hidden by the near field). `exact` itself is a candidate, estimated at its own accuracy
// against Monte Carlo (a constant band in the model registry); the others' errors are against
// `exact` and do not add its band (as the Monte Carlo noise was not added before). About 0.1-3 ms
// per channel (quantized diffusion dominates).
//
// Outside that domain the errors come from tools/validation/models_vs_montecarlo_extended.tsv
// (validate_models: 72 cases, alpha' 0.5-0.999 x eta 1, 1.3, 1.4, 1.5 x g 0, 0.9, 0.95, 2M
// photons each, Monte Carlo noise about 1.5 % in area-weighted L2), embedded in the library: at
// given coefficients a model's error is the worst over the measured cases that bracket them (not
// interpolated: conservative); alpha' above 0.999 uses the 0.999 cases. Beyond both there is no
// estimate and no choice: the refusal names the channel and points to `bssrdf reference`.
// A model's cost is one R(r) evaluation measured by bench_models.
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
  double cost_ns = 0;      // one R(r) evaluation (bench_models median, alpha' 0.9, eta 1.3)
  double total_error = 0;  // |relative error of the total reflectance|
  // Relative L2 error of the profile, single scattering included: against `exact`, the larger of
  // near_error and far_error; from the table, the area-weighted L2 of R(r) against Monte Carlo.
  double profile_error = 0;
  double near_error = 0, far_error = 0;  // against `exact`: inside / beyond one transport mfp (0 from the table)
  std::string source;  // "exact" (measured live), "table" (the Monte Carlo table), "exact+table" (channels differ)
  // The model's own verdict here: its first "invalid" validity note ("code: message"), empty when it
  // has none. An invalid model is never chosen, whatever its measured error.
  std::string invalid;
  double error() const { return total_error > profile_error ? total_error : profile_error; }
};

// Every candidate model, cheapest first, with its estimated errors at these coefficients: live
// against `exact` inside its domain, else from the table; nullopt outside both.
std::optional<std::vector<ModelErrorEstimate>> estimate_model_errors(const Reduced<double>& m);
// One model's estimate, as estimate_model_errors gives it, measuring only that model: nullopt
// where that gives none or when `model` is not a candidate.
std::optional<ModelErrorEstimate> estimate_model_error(const std::string& model, const Reduced<double>& m);
// The two sources alone: nullopt outside the exact domain / outside the table's measured ranges
// (alpha' < 0.5, eta outside [1, 1.5], g outside [0, 0.95]).
std::optional<std::vector<ModelErrorEstimate>> model_errors_vs_exact(const Reduced<double>& m);
std::optional<std::vector<ModelErrorEstimate>> tabulated_model_errors(const Reduced<double>& m);

// The same for a medium: the worst over its channels, cheapest first. Throws InvalidInput naming
// the channel and the ranges when a channel is outside them.
std::vector<ModelErrorEstimate> estimate_model_errors(const Medium& medium);

// Every candidate with a table column, with its cost and its errors in all measured cases (the validation table, in its
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

// The default profile model, decided here and nowhere else (every command without --model takes
// it): `exact`, the radiative-transfer solution, wherever every channel is inside its domain;
// otherwise the most accurate valid model measured there, by its worst channel: live against
// `exact` for the channels inside, from the Monte Carlo table where it has the channel, else
// from the model's total-error bands against adding-doubling (model registry).
struct DefaultModel {
  std::string name;
  std::string reason;  // why it is not `exact`: the channel and parameter outside, the error used; empty for exact
};
DefaultModel default_model(const Medium& medium);
DefaultModel default_model(const Reduced<double>& m);
// For a fit, whose albedo is what it finds: `exact` when every g and every eta in [eta_min,
// eta_max] are inside its domain (it spans every albedo); otherwise default_model() of the medium
// with those g at alpha' 0.9 and eta_max, which the reason states.
DefaultModel default_model_over_albedos(const std::vector<double>& g, double eta_min, double eta_max);

}  // namespace bssrdf
