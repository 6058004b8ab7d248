// How wrong the reference itself may look: its measured accuracy translated into the image-space
// error (image_error.hpp), so that a candidate that IS the reference (the `exact` model judged
// against the exact model, the reference's own table) is not judged at error 0.
//
// The rule (one formula for every reference):
//   U = B + 2 N,
//  - N: the reference's Monte Carlo noise, one standard error in code values (ImageError::reference_noise;
//    0 for a formula). Two standard errors, as `reference-table` was always stated.
//  - B: the band error. Each channel with a measured band (ReferenceSource: total T, shape P; the
//    exact model's is its registry band at the channel's alpha' and g, measured against fresh Monte
//    Carlo: total 0.6 %, shape 3 % anywhere, 0.3 % and 1.8 % for 0.05 <= alpha' <= 0.9999, g <= 0.9)
//    is perturbed within it,
//      R'(r) = (1 + s_T T) (1 + s_P e(r)) R(r),   e(r) = +e_near inside one transport mfp, -e_far beyond,
//    with e_near f = e_far (1 - f) (f: the reference's fraction of light inside one transport mfp; the
//    shape change keeps the total, as the exact profile is scaled to its tabulated total) and
//    max(e_near, e_far) = P (a constant factor over a region has relative L2 equal to it: the band's
//    measure, the larger of the near and far L2 of r R(r)). B is the largest image error, over the
//    four signs s_T, s_P = +-1, of the perturbed reference against the reference.
// Candidates that are the reference's own source carry max(their judged error, U); its table carries
// U plus its tabulation error (advise.hpp). Other candidates are judged against the reference as it is
// (as --model auto does), and U is reported beside them.
//
//   ReferenceUncertainty u = reference_uncertainty(judge, reference, near_radius);
//   u.error();   // code values
#pragma once

#include <vector>

#include "bssrdf/image/annular_profile.hpp"
#include "bssrdf/image/image_error.hpp"
#include "bssrdf/image/realtime_tables.hpp"
#include "bssrdf/image/reference_profile.hpp"

namespace bssrdf {

struct ReferenceUncertainty {
  ImageError band;   // B: the worst perturbed reference against the reference (error 0 without bands)
  double noise = 0;  // N: one standard error, code values
  double error() const { return band.error + 2 * noise; }
};

// The reference perturbed within its bands with signs total_sign, shape_sign (+1 or -1); channels
// without a band are unchanged. near_radius: one transport mean free path per channel, mm.
std::vector<AnnularProfile> perturbed_reference(const ReferenceProfiles& reference,
                                                const std::vector<double>& near_radius, int total_sign, int shape_sign);

// U for a reference rendered in `judge` (the RealtimeJudge of the same reference and pixel size).
ReferenceUncertainty reference_uncertainty(const RealtimeJudge& judge, const ReferenceProfiles& reference,
                                           const std::vector<double>& near_radius);

}  // namespace bssrdf
