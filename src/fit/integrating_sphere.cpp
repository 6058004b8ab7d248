// iad 4's sphere equations; see integrating_sphere.hpp.
#include "bssrdf/fit/integrating_sphere.hpp"

#include <algorithm>
#include <cmath>

namespace bssrdf {

namespace {

struct Sphere {
  double a_s, a_t, a_d, a_w, r_w, r_d;
  bool baffle;
};

Sphere sphere_of(const RxtSphere& s, double r_d, bool baffle) {
  auto fraction = [&](double d) { return s.diameter > 0 ? d * d / (4 * s.diameter * s.diameter) : 0.0; };
  Sphere p{
      fraction(s.sample_port), fraction(s.third_port), fraction(s.detector_port), 0, s.wall_reflectance, r_d, baffle};
  p.a_w = 1 - p.a_s - p.a_t - p.a_d;
  return p;
}

// Gain of the sphere's wall irradiance over a black sphere's (iad's Gain).
double gain(const Sphere& p, double r_sample, double r_third) {
  if (p.baffle)
    return 1 / (1 - (p.r_w + p.a_t / p.a_w * r_third) * (p.a_w + (1 - p.a_t) * (p.a_d * p.r_d + p.a_s * r_sample)));
  return 1 / (1 - p.a_w * p.r_w - p.a_d * p.r_d - p.a_s * r_sample - p.a_t * r_third);
}

}  // namespace

std::pair<double, double> sphere_measurements(const RxtSetup& setup, const SphereModel& model, const SampleTotals& t) {
  const double c = std::isnan(model.unscattered_in_m_r) ? setup.unscattered_in_m_r : model.unscattered_in_m_r;
  const double C = std::isnan(model.unscattered_in_m_t) ? setup.unscattered_in_m_t : model.unscattered_in_m_t;
  const double f = model.wall_first;
  // The totals less the unscattered light the spheres do not collect.
  const double ur1 = std::max(0.0, t.ur1 - (1 - c) * t.ru), ut1 = std::max(0.0, t.ut1 - (1 - C) * t.tu);
  if (setup.spheres == 0 || (setup.spheres == 1 && model.dual_beam)) return {ur1, ut1};
  const Sphere r = sphere_of(setup.reflection, model.detector_reflectance, model.baffle_r);
  const Sphere x = sphere_of(setup.transmission, model.detector_reflectance, model.baffle_t);
  const double r_std = setup.standard_reflectance;
  if (setup.spheres == 1) {
    // Reflection: scattered light (UR1 - R_u) bounces once off the wall past the baffle, the
    // specular part c R_u lands on the wall; normalised by the standard (and by the reading with
    // the sample port empty, which f > 0 makes non-zero).
    const double r_first = r.baffle ? r.r_w * (1 - r.a_t) : 1;
    const double scattered_r = std::max(0.0, t.ur1 - t.ru);
    const double p_std = gain(r, r_std, 0) * (r_std * (1 - f) + f * r.r_w);
    const double p_0 = gain(r, 0, 0) * f * r.r_w;
    const double p = gain(r, t.uru, 0) * (r_first * (scattered_r * (1 - f) + f * r.r_w) + r.r_w * (1 - f) * c * t.ru);
    const double m_r = r_std * (p - p_0) / (p_std - p_0);
    // Transmission: the third port holds the standard t_std when the unscattered beam is
    // collected, else it is open; a sphere without one calibrates on its wall.
    double r_cal = setup.standard_transmittance, r_third = setup.standard_transmittance;
    if (x.a_t == 0)
      r_cal = r_third = x.r_w;
    else if (!(C > 0))
      r_third = 0;
    const double x_first = x.baffle ? x.r_w * (1 - x.a_t) + r_third * x.a_t : 1;
    const double scattered_t = std::max(0.0, t.ut1 - t.tu);
    const double m_t = (r_third * t.tu * C + x_first * scattered_t) * gain(x, t.uru, r_third) / gain(x, 0, r_cal);
    return {m_r, m_t};
  }
  // Two spheres (iad's Two_Sphere_R and Two_Sphere_T): the gains coupled through UTU.
  auto detectors = [&](double ur1_, double uru, double uru_t, double ut1_, double utu) {
    const double g_r = gain(r, uru, 0), g_t = gain(x, uru_t, 0);
    const double coupling = 1 - r.a_s * x.a_s * r.a_w * x.a_w * (1 - r.a_t) * (1 - x.a_t) * g_r * g_t * utu * utu;
    const double d_r = r.a_d * (1 - r.a_t) * r.r_w * g_r / coupling *
                       ((1 - f) * ur1_ + r.r_w * f + (1 - f) * x.a_s * (1 - x.a_t) * x.r_w * ut1_ * utu * g_t);
    const double d_t = x.a_d * (1 - x.a_t) * x.r_w * g_t / coupling *
                       ((1 - f) * ut1_ + (1 - r.a_t) * r.r_w * r.a_s * utu * (f * r.r_w + (1 - f) * ur1_) * g_r);
    return std::pair{d_r, d_t};
  };
  const auto zero = detectors(0, 0, 0, 0, 0);
  const auto sample = detectors(ur1, t.uru, t.uru, ut1, t.utu);
  const double m_r = r_std * (sample.first - zero.first) / (detectors(r_std, r_std, r_std, 0, 0).first - zero.first);
  const double m_t = (sample.second - zero.second) / (detectors(0, 0, 0, 1, 1).second - zero.second);
  return {m_r, m_t};
}

}  // namespace bssrdf
