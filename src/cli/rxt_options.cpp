// Instrument options of 'fit slab --rxt'; see rxt_options.hpp.
#include "rxt_options.hpp"

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
}

bool any_rxt_sphere_option(const RxtSphereOptions& o) {
  return o.baffles != "both" || !o.wall_first.empty() || !o.detector_reflectance.empty() ||
         !o.unscattered_in_m_r.empty() || !o.unscattered_in_m_t.empty() || o.dual_beam || o.quadrature != 0;
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
}

}  // namespace bssrdf::cli
