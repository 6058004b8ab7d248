// The cheapest representation of a material that looks right at a scene's pixel size: every
// candidate is rendered through the image-space error (image_error.hpp) against the reference
// (reference_profile.hpp) and the cheapest one within the tolerance for the target is chosen.
//
//   Advice a = advise(skin, MonteCarloReference({}), {.pixel = 0.1, .tolerance = 1});
//   if (a.choice) std::cout << a.candidates[*a.choice].representation;
//
// Candidates (cost: nanoseconds of profile work per evaluation at a shading point, the unit every
// candidate shares; ties ordered by memory):
//  - "lambertian": no subsurface transport, the reference's diffuse reflectance as albedo. Cost 0.
//  - every analytic model of the registry (dipole, better-dipole, burley, ..., quantized+ss): cost
//    one R(r) evaluation as measured by bench_models (model_choice.hpp).
//  - the real-time tables of the analytic model with the smallest image error, each sized by the
//    tolerance (realtime_tables.hpp: the smallest within it, else the most accurate tried):
//    "radial-table-N:MODEL" (N radii of radial_table_nodes(), linear in (ln r, ln R), 0 beyond; N = 8 to 256; cost
//    kTableLookupNs, memory N x channels x 4 bytes); "gaussians-K:MODEL" (K = 1 to 8 shared-variance Gaussians,
//    fitted_mixture_table, the texture-space / GPU Gems 3 form; cost K x kGaussianTermNs, memory K x (channels + 1) x
//    4); "separable-N:MODEL" (Jimenez et al. 2015, N taps and the range in `parameters`; cost 2 N x kKernelTapNs,
//    memory N x 4 floats); "preintegrated-N:MODEL" (Penner & Borshukov 2011, N x N; cost kTableLookupNs, memory N^2 x
//    channels x 4).
//  - "exact" (when every channel is inside its table): the exact model, cost one R(r) of the registry.
//  - "reference-table": the reference itself tabulated. A Monte Carlo reference: its annuli (what `lut
//    --kind radial --reference` writes), memory annuli x channels x 4 bytes. A reference with formula
//    channels (exact, or auto's shape models): R(r) of each at N radii as radial_table_nodes() places
//    them (N = 8 to 256, the smallest with U + its tabulation error within the tolerance; Monte Carlo
//    channels of a mixed reference: their annulus means at those radii), memory N x channels x 8 bytes.
//    Cost kTableLookupNs.
// A candidate that IS the reference cannot be judged against it (it would score 0): the reference's
// own uncertainty U (reference_uncertainty.hpp: its measured band in image space plus twice its
// Monte Carlo noise) stands in. "reference-table" carries U + its tabulation error; a model that is
// the source of any reference channel (`exact` against the exact reference) carries max(judged, U).
// The other candidates are judged against the reference as it is; U is reported beside them.
// Real-time targets keep the candidates a shader evaluates in closed form or by one lookup:
// lambertian, dipole, better-dipole, the burley variants and the tables.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bssrdf/advise/reference_uncertainty.hpp"
#include "bssrdf/image/image_error.hpp"
#include "bssrdf/image/realtime_tables.hpp"
#include "bssrdf/image/reference_profile.hpp"
#include "bssrdf/medium.hpp"
#include "bssrdf/model.hpp"

namespace bssrdf {

// One lookup of a radial table (a log, a floor, a lerp and an exp), ns, and one Gaussian term: the
// ratios to the dipole's R(r) measured by tools/bench/bench_advise (0.68 and 1.88 / 8 for 8
// Gaussians, median of 3, loaded 2-core machine) times the dipole's 19 ns of bench_models, so that
// they rank with the models' costs.
inline constexpr double kTableLookupNs = 13;
inline constexpr double kGaussianTermNs = 4.5;
// One tap of a separable screen-space kernel (a linearly interpolated read of an RGB irradiance row
// and a multiply-add), measured the same way by bench_advise (0.14-0.25 of the dipole on the loaded
// machine, so 2.7-4.7 ns); a kernel of N taps costs 2 N taps a
// pixel (a horizontal and a vertical pass).
inline constexpr double kKernelTapNs = 4;

enum class AdviseTarget { realtime, offline, any };
AdviseTarget parse_advise_target(const std::string& text);  // throws InvalidInput naming "--target"
std::string_view to_string(AdviseTarget target);

struct AdviseOptions {
  double pixel = 0.1;    // mm per pixel
  double tolerance = 1;  // largest acceptable image error, 8-bit sRGB code values
  AdviseTarget target = AdviseTarget::any;
  double object_size = 0;  // mm; 0: not given
};

struct AdviseCandidate {
  std::string representation;
  ImageError image;  // .error: the predicted image-space error
  double cost = 0;   // ns per evaluation
  std::size_t memory_bytes = 0;
  bool realtime = false;
  bool meets_tolerance = false;
  std::vector<std::pair<std::string, double>> parameters;  // a table's chosen size, a kernel's taps and range (mm), ...
};

struct Advice {
  AdviseOptions options;
  std::string reference;  // its description
  double reference_seconds = 0;
  double reference_noise = 0;                  // largest over the candidates' comparisons (code values)
  ReferenceUncertainty reference_uncertainty;  // U: how wrong the reference itself may look (code values)
  std::vector<std::string> reference_sources;  // per channel: "exact", "montecarlo" or a shape model
  // The reference-table candidate's nodes per channel, as judged (empty: a Monte Carlo reference, whose
  // table is its own run); `--write` writes them.
  std::vector<RadialTableNodes> reference_table;
  std::vector<double> diffuse_reflectance;  // the reference's, per channel (the Lambertian albedo)
  std::vector<AdviseCandidate> candidates;  // cheapest first (all, whatever the target)
  std::optional<std::size_t> choice;        // index into candidates: cheapest within tolerance for the target
  double profile_radius = 0;                // mm: the radius holding 99 % of the reference's light, widest channel
  std::string object_warning;               // non-empty when 2 profile_radius exceeds options.object_size
};

Advice advise(const Medium& medium, const ReferenceProfile& reference, const AdviseOptions& options);

// JSON (names fixed by issue 16): {"choice": {"representation", "error", "cost", "memory_bytes",
// ...} or null, "candidates": [{"representation", "error", "cost", "meets_tolerance", ...}],
// "pixel_mm", "tolerance", "target", "reference", "reference_noise",
// "reference_uncertainty" (U), "reference_band_error" (its band part), "reference_sources" (per channel),
// "profile_radius_mm", "warnings"}.
std::string to_json(const Advice& advice, const std::string& material);
// A table for people: the candidates, the choice and why the cheaper ones fail.
std::string to_table(const Advice& advice, const std::string& material);

}  // namespace bssrdf
