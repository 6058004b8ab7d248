// Single- and double-integrating-sphere equations; see integrating_sphere.hpp.
#include "bssrdf/fit/integrating_sphere.hpp"

namespace bssrdf {

namespace {

struct Ports {
  double a_s, a_e, a_d, a_w, r_w;
};

Ports ports_of(const RxtSphere& s) {
  auto fraction = [&](double d) { return d * d / (4 * s.diameter * s.diameter); };
  Ports p{fraction(s.sample_port), fraction(s.third_port), fraction(s.detector_port), 0, s.wall_reflectance};
  p.a_w = 1 - p.a_s - p.a_e - p.a_d;
  return p;
}

// Gain of the detector's irradiance relative to a black sphere, with a baffle between sample and
// detector and a black detector.
double gain(const Ports& p, double r_sample) { return 1 / (1 - p.r_w * (p.a_w + (1 - p.a_e) * p.a_s * r_sample)); }

}  // namespace

std::pair<double, double> sphere_measurements(const RxtFile& setup, const SampleTotals& t) {
  if (setup.spheres == 0) return {t.ur1, t.ut1};
  const Ports r = ports_of(setup.reflection), x = ports_of(setup.transmission);
  const double r_std = setup.standard_reflectance;
  if (setup.spheres == 1) return {t.ur1 * gain(r, t.uru) / gain(r, r_std), t.ut1 * gain(x, t.uru) / gain(x, 0)};
  // Two spheres: light diffused in one sphere crosses the sample (UTU) into the other and back.
  auto coupling = [&](double uru, double utu) {
    return 1 - r.a_s * x.a_s * r.r_w * x.r_w * (1 - r.a_e) * (1 - x.a_e) * gain(r, uru) * gain(x, uru) * utu * utu;
  };
  auto detector_r = [&](double ur1, double uru, double ut1, double utu) {
    return r.a_d * (1 - r.a_e) * r.r_w * gain(r, uru) / coupling(uru, utu) *
           (ur1 + x.a_s * (1 - x.a_e) * x.r_w * ut1 * utu * gain(x, uru));
  };
  auto detector_t = [&](double ur1, double uru, double ut1, double utu) {
    return x.a_d * (1 - x.a_e) * x.r_w * gain(x, uru) / coupling(uru, utu) *
           (ut1 + (1 - r.a_e) * r.r_w * r.a_s * utu * ur1 * gain(r, uru));
  };
  const double m_r = r_std * detector_r(t.ur1, t.uru, t.ut1, t.utu) / detector_r(r_std, r_std, 0, 0);
  const double m_t = detector_t(t.ur1, t.uru, t.ut1, t.utu) / detector_t(0, 0, 1, 1);
  return {m_r, m_t};
}

}  // namespace bssrdf
