// The real-time tables sized by the image-space error (image_error.hpp) instead of fixed counts:
// the smallest separable kernel, pre-integrated LUT, Gaussian sum and radial table of a model whose
// rendering of the test patterns at a pixel size is within a tolerance (8-bit sRGB code values) of a
// reference's. `bssrdf advise` offers them as candidates and `bssrdf lut --tolerance T --pixel P`
// sizes its tables with them; each records the error it reached.
//
//   const RealtimeJudge judge(meter, reference_images, albedo);
//   SeparableChoice s = choose_separable_kernel(skin, projections, judge, 1.0);
//   if (s.meets_tolerance) use(s.options);   // else s is the most accurate kernel tried
//
// What each one renders (the patterns of image_error.hpp):
//  - separable kernel (Jimenez et al. 2015): its taps in screen space (ImageErrorMeter::render_taps),
//    times the model's total reflectance (the diffuse colour bssrdf:total_reflectance it records).
//    Tried: taps 5 to 255 (kSeparableTaps), each with the range holding 95 % to 99.999 % of the
//    widest channel's light (kSeparableBands); the fewest taps within the tolerance win, then the
//    smallest error among their ranges.
//  - pre-integrated LUT (Penner & Borshukov 2011), square, N = 16 to 256: the LUT blurs across
//    curvature, not across a shadow edge, so on the flat patterns it is a Lambertian surface of
//    albedo x D(N.L = 1, flattest row) as a clamped bilinear fetch reads it; and over its domain its
//    bilinear interpolation differs from D itself (measured at the texel centres of the 2N table,
//    shown as sRGB codes of albedo x D). The error is the larger of the two; the smallest N whose
//    interpolation error is within the tolerance wins.
//  - Gaussian sum (fitted_mixture_table), K = 1 to 8, and radial table (radial_table(), N radii,
//    linear in (ln r, ln R)), N = 8 to 256: their profiles on the reference's annuli; the smallest
//    within the tolerance wins.
// When no size meets the tolerance the most accurate one tried is returned, meets_tolerance false.
// The Gaussian count stops growing once it no longer cuts the error by 10 % (the fitted model's own
// error dominates; fits get slow), and a pre-integrated LUT grows only while its interpolation
// error exceeds both the tolerance and its flat patterns' error. A kernel's error is not monotonic
// in its taps (sparse taps alias against the pixels: Skin1 at 1 mm, 99.9 % band, 29 code values at
// 11 taps, 39 at 13, 9.7 at 17), so every size is tried.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "bssrdf/image/image_error.hpp"
#include "bssrdf/image/reference_profile.hpp"
#include "bssrdf/lut/gaussian_mixture_table.hpp"
#include "bssrdf/lut/preintegrated_table.hpp"
#include "bssrdf/lut/projected_profile.hpp"
#include "bssrdf/lut/radial_table.hpp"
#include "bssrdf/lut/separable_kernel.hpp"
#include "bssrdf/medium.hpp"
#include "bssrdf/model.hpp"

namespace bssrdf {

struct RadialTableNodes {
  std::vector<double> radius, value;  // mm, 1/mm^2
};

// The radial-table candidate: R(r) of `model` at n >= 2 radii geometric over [lo_ell ell, outer]
// (ell: transport mean free path; outer: hi_ell ell, or with hi_ell = 0 profile_extent(m), as far
// as the reference's annuli reach), linear in (ln r, ln R) between them, R(r_0)
// below and 0 beyond (the table a renderer loads; `advise --write` writes these nodes).
RadialTableNodes radial_table_nodes(const Model& model, const Reduced<double>& m, std::size_t n, double lo_ell = 1e-3,
                                    double hi_ell = 0);
// The same nodes of any R(r) (a reference channel's formula).
RadialTableNodes radial_table_nodes(const std::function<double(double)>& reflectance, const Reduced<double>& m,
                                    std::size_t n, double lo_ell = 1e-3, double hi_ell = 0);
std::function<double(double)> radial_table(const RadialTableNodes& nodes);
std::function<double(double)> radial_table(const Model& model, const Reduced<double>& m, std::size_t n,
                                           double lo_ell = 1e-3, double hi_ell = 0);

inline constexpr std::array<int, 15> kSeparableTaps = {5, 7, 9, 11, 13, 17, 21, 25, 33, 49, 65, 97, 129, 193, 255};
inline constexpr std::array<double, 5> kSeparableBands = {0.95, 0.99, 0.999, 0.9999, 0.99999};
inline constexpr std::array<std::size_t, 5> kPreintegratedSizes = {16, 32, 64, 128, 256};
// Radii the Gaussian sums are fitted on (fitted_mixture_table's samples): 32 fit as well as 128 in
// relative L2 (Chicken1, 8 Gaussians: 0.0064 and 0.0063) in a tenth of the time (0.05 s, 0.58 s).
inline constexpr std::size_t kGaussianFitSamples = 32;
inline constexpr std::array<int, 5> kGaussianCounts = {1, 2, 4, 6, 8};  // 16: a 3 s fit, no better
inline constexpr std::array<std::size_t, 6> kRadialTableSizes = {8, 16, 32, 64, 128, 256};

// The reference as rendered once, with the meter that rendered it and the albedo (diffuse
// reflectance per channel) a representation without its own colour is shown with.
struct RealtimeJudge {
  ImageErrorMeter meter;
  std::vector<PatternImage> reference;
  std::vector<double> albedo;
  ImageError error(const std::vector<AnnularProfile>& candidate) const;
  ImageError error(const std::vector<PatternImage>& candidate) const { return meter.error(reference, candidate); }
};

// The reference's profiles for `medium`, rendered once at `pixel` (mm), its albedo its totals.
RealtimeJudge judge_against(const Medium& medium, const ReferenceProfile& reference, double pixel);

struct SeparableChoice {
  SeparableKernelOptions options;  // taps, range (mm) and the band it holds
  ImageError image;
  bool meets_tolerance = false;
};
// The image of a built kernel (per channel: taps at offset x range, the model's total as colour).
std::vector<PatternImage> render_separable(const ImageErrorMeter& meter, const SeparableKernel& kernel);
SeparableChoice choose_separable_kernel(const Medium& medium,
                                        const std::vector<std::optional<ProjectedProfile>>& profiles,
                                        const RealtimeJudge& judge, double tolerance);

struct PreintegratedChoice {
  std::size_t size = 0;      // N x N
  ImageError image;          // the larger of the flat patterns' and the table's
  double table_error = 0;    // the bilinear interpolation's, code values
  double curvature_max = 0;  // 1/mm, as the table is built
  bool meets_tolerance = false;
};
// The interpolation error of `table` against `finer` (the same model, twice the size, the same
// curvature_max), in code values of albedo x D, largest over texels and channels.
double preintegrated_table_error(const PreintegratedTable& table, const PreintegratedTable& finer,
                                 const std::vector<double>& albedo);
// stop_at_flat_error: stop growing once the interpolation error is below the flat patterns' (the
// candidate cannot meet the tolerance then; `advise`); false: grow until the interpolation alone is
// within the tolerance (`lut --kind preintegrated`, whose LUT is wanted for curvature anyway).
PreintegratedChoice choose_preintegrated_table(const Medium& medium,
                                               const std::vector<std::optional<ProjectedProfile>>& profiles,
                                               const RealtimeJudge& judge, double tolerance,
                                               bool stop_at_flat_error = true);

struct CountChoice {
  std::size_t count = 0;  // Gaussians, or radii
  ImageError image;
  bool meets_tolerance = false;
};
CountChoice choose_gaussian_count(const Medium& medium, const Model& model, const RealtimeJudge& judge,
                                  double tolerance);
CountChoice choose_radial_table_size(const Medium& medium, const Model& model, const RealtimeJudge& judge,
                                     double tolerance);

// The profiles on the judge's annuli of K fitted Gaussians and of an N-radius table.
std::vector<AnnularProfile> gaussian_sum_profiles(const Medium& medium, const Model& model, int count,
                                                  const std::vector<double>& edges);
std::vector<AnnularProfile> radial_table_profiles(const Medium& medium, const Model& model, std::size_t radii,
                                                  const std::vector<double>& edges);

// `bssrdf lut --pixel P [--tolerance T]`: how wrong a written table looks, and (with T) its size
// chosen by it. The judge is the model the table tabulates (ModelReference): the table's own error
// at that pixel size; the model's error against the truth is what `bssrdf advise` adds.
ImageError image_error_of(const RealtimeJudge& judge, const SeparableKernel& kernel);
ImageError image_error_of(const RealtimeJudge& judge, const GaussianMixtureTable& table);
ImageError image_error_of(const RealtimeJudge& judge, const RadialTable& table);
// The pre-integrated LUT: the larger of its flat patterns' and its interpolation error (against the
// table twice as fine, built from `profiles` over the same curvature range).
ImageError image_error_of(const RealtimeJudge& judge, const PreintegratedTable& table, const Medium& medium,
                          const std::vector<std::optional<ProjectedProfile>>& profiles);
// The loosest relative interpolation tolerance of build_radial_table (1e-1 to 1e-4 in steps of
// about 3) whose table is within `tolerance` code values; else the tightest.
struct RadialToleranceChoice {
  double relative_tolerance = 1e-3;
  ImageError image;
  bool meets_tolerance = false;
};
RadialToleranceChoice choose_radial_tolerance(const Medium& medium, const Model& model, const RealtimeJudge& judge,
                                              double tolerance, RadialTableOptions options);

}  // namespace bssrdf
