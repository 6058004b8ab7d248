#include "bssrdf/advise/reference_uncertainty.hpp"

#include <algorithm>
#include <cmath>

namespace bssrdf {

std::vector<AnnularProfile> perturbed_reference(const ReferenceProfiles& reference,
                                                const std::vector<double>& near_radius, int total_sign,
                                                int shape_sign) {
  std::vector<AnnularProfile> out = reference.channels;
  for (std::size_t c = 0; c < out.size(); ++c) {
    const ReferenceSource& source = reference.sources[c];
    AnnularProfile& p = out[c];
    // An annulus is near when its geometric centre (the first: all of it) lies inside one transport mfp.
    std::vector<bool> near(p.energy.size());
    double inside = 0;
    for (std::size_t i = 0; i < p.energy.size(); ++i) {
      near[i] = i == 0 || std::sqrt(p.edges[i] * p.edges[i + 1]) < near_radius[c];
      if (near[i]) inside += p.energy[i];
    }
    const double total = p.total(), f = total > 0 ? inside / total : 0;
    double e_near = 0, e_far = 0;  // no shape change keeps the total when all light is on one side
    if (f > 0 && f < 1) {
      e_far = std::min(source.profile_band, source.profile_band * f / (1 - f));
      e_near = e_far * (1 - f) / f;
    }
    const double scale = 1 + total_sign * source.total_band;
    for (std::size_t i = 0; i < p.energy.size(); ++i)
      p.energy[i] *= scale * (1 + shape_sign * (near[i] ? e_near : -e_far));
  }
  return out;
}

ReferenceUncertainty reference_uncertainty(const RealtimeJudge& judge, const ReferenceProfiles& reference,
                                           const std::vector<double>& near_radius) {
  ReferenceUncertainty u;
  u.noise = judge.error(reference.channels).reference_noise;
  const bool banded = std::any_of(reference.sources.begin(), reference.sources.end(),
                                  [](const auto& s) { return s.total_band > 0 || s.profile_band > 0; });
  if (!banded) return u;
  for (int total_sign : {-1, 1})
    for (int shape_sign : {-1, 1}) {
      const ImageError e = judge.error(perturbed_reference(reference, near_radius, total_sign, shape_sign));
      if (e.error > u.band.error) u.band = e;
    }
  return u;
}

}  // namespace bssrdf
