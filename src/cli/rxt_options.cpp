// Instrument options of 'fit slab --rxt'; see rxt_options.hpp.
#include "rxt_options.hpp"

#include <sstream>
#include <vector>

#include "cli_common.hpp"

namespace bssrdf::cli {

void add_rxt_sphere_options(CLI::App& c, RxtSphereOptions& o) {
  c.add_option("--baffles", o.baffles,
               "--rxt: baffle between sample and detector in the spheres: both, reflection, transmission, none "
               "[both, iad -H 3]");
  c.add_option("--wall-first", o.wall_first,
               "--rxt: fraction of the beam hitting the reflection sphere's wall first [0, iad -f]");
  c.add_option("--detector-reflectance", o.detector_reflectance, "--rxt: reflectance of the detectors [0, as iad]");
  c.add_option("--unscattered-in-mr", o.unscattered_in_m_r,
               "--rxt: fraction of the unscattered reflection the sphere collects in M_R [the file's, else 1; iad -c]");
  c.add_option("--unscattered-in-mt", o.unscattered_in_m_t,
               "--rxt: fraction of the unscattered transmission collected in M_T [the file's, else 1; iad -C]");
  c.add_flag("--dual-beam", o.dual_beam, "--rxt: dual-beam (comparison) sphere: no gain correction [off, iad -X]");
  c.add_option("--quadrature", o.quadrature,
               "Quadrature angles per hemisphere, as iad's -q (iad's default is 8) [automatic: 32]");
  c.add_option(
      "--incidence-angle", o.incidence,
      "--rxt: angle of incidence of the beam in degrees, for every row (iad -i) [the file's column i, else 0]");
  c.add_option("--fixed-albedo", o.albedo, "--rxt: hold the albedo mu_s/(mu_a + mu_s) (iad -a) [none]");
  c.add_option("--fixed-optical-thickness", o.optical_thickness,
               "--rxt: hold the optical thickness (mu_a + mu_s) d (iad -b) [none]");
  c.add_option("--fixed-mu-a", o.mu_a, "--rxt: hold mu_a in 1/mm (iad -A) [none]");
  c.add_option("--fixed-mu-s", o.mu_s,
               "--rxt: hold mu_s in 1/mm, or per wavelength 'P lambda0 mu_s0 gamma': mu_s0 (lambda/lambda0)^gamma "
               "(iad -F) [none]");
  c.add_option("--fixed-mu-s-prime", o.mu_s_prime,
               "--rxt: hold mu_s = mu_s'/(1 - g) with --g, else mu_s = mu_s' as iad -j does [none]");
}

bool any_rxt_sphere_option(const RxtSphereOptions& o) {
  return o.baffles != "both" || !o.wall_first.empty() || !o.detector_reflectance.empty() ||
         !o.unscattered_in_m_r.empty() || !o.unscattered_in_m_t.empty() || o.dual_beam || o.quadrature != 0 ||
         !o.albedo.empty() || !o.optical_thickness.empty() || !o.mu_a.empty() || !o.mu_s.empty() ||
         !o.mu_s_prime.empty() || !o.incidence.empty();
}

void apply_rxt_sphere_options(const RxtSphereOptions& o, RxtFitOptions& options) {
  auto& m = options.sphere;
  if (o.baffles == "both" || o.baffles == "none" || o.baffles == "reflection" || o.baffles == "transmission") {
    m.baffle_r = o.baffles == "both" || o.baffles == "reflection";
    m.baffle_t = o.baffles == "both" || o.baffles == "transmission";
  } else {
    throw InvalidInput("--baffles", o.baffles, "both, reflection, transmission or none");
  }
  if (!o.wall_first.empty()) m.wall_first = parse_number(o.wall_first, "--wall-first");
  if (!o.detector_reflectance.empty())
    m.detector_reflectance = parse_number(o.detector_reflectance, "--detector-reflectance");
  if (!o.unscattered_in_m_r.empty()) m.unscattered_in_m_r = parse_number(o.unscattered_in_m_r, "--unscattered-in-mr");
  if (!o.unscattered_in_m_t.empty()) m.unscattered_in_m_t = parse_number(o.unscattered_in_m_t, "--unscattered-in-mt");
  m.dual_beam = o.dual_beam;
  options.quadrature = o.quadrature;
  if (!o.incidence.empty()) options.incidence_degrees = parse_number(o.incidence, "--incidence-angle");
  auto& k = options.constraints;
  if (!o.albedo.empty()) k.albedo = parse_number(o.albedo, "--fixed-albedo");
  if (!o.optical_thickness.empty())
    k.optical_thickness = parse_number(o.optical_thickness, "--fixed-optical-thickness");
  if (!o.mu_a.empty()) k.mu_a = parse_number(o.mu_a, "--fixed-mu-a");
  if (!o.mu_s_prime.empty()) k.mu_s_prime = parse_number(o.mu_s_prime, "--fixed-mu-s-prime");
  if (o.mu_s.empty()) return;
  if (o.mu_s[0] != 'P' && o.mu_s[0] != 'p') {
    k.mu_s = parse_number(o.mu_s, "--fixed-mu-s");
    return;
  }
  std::istringstream words(o.mu_s.substr(1));
  std::vector<std::string> law;
  for (std::string w; words >> w;) law.push_back(w);
  if (law.size() != 3)
    throw InvalidInput("--fixed-mu-s", o.mu_s, "a number or 'P lambda0 mu_s0 gamma' (e.g. 'P 500 1.0 -1.3')");
  k.power_lambda0 = parse_number(law[0], "--fixed-mu-s lambda0");
  k.power_mu_s0 = parse_number(law[1], "--fixed-mu-s mu_s0");
  k.power_gamma = parse_number(law[2], "--fixed-mu-s gamma");
}

}  // namespace bssrdf::cli
