// Cost of one profile evaluation R(r) per model at its default tolerance (ns, medians), and photon
// beam diffusion against pbrt-v3/v4's scheme (100 + 100 midpoint samples of the exponential, the
// published anchor: about 6.3 us per evaluation on this machine kind) run in the same process,
// with the accuracy of both against a converged reference (1024-point Gauss-Legendre).
//
//   bench_models [repetitions=15]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <vector>

#include "bssrdf/fresnel.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/models/exact.hpp"
#include "bssrdf/models/photon_beam_diffusion.hpp"
#include "bssrdf/single_scattering.hpp"
#include "median_timing.hpp"
#include "pbrt_style.hpp"

using namespace bssrdf;
using bssrdf::bench::median_ns_per_call;
using bssrdf::bench::pbrt_style_pbd;

namespace {}  // namespace

int main(int argc, char** argv) {
  const int repetitions = argc > 1 ? std::max(1, std::atoi(argv[1])) : 15;
  // Optical units: sigma_t' = 1; 64 log-spaced radii from 0.01 to 20 transport mean free paths.
  std::vector<double> radii;
  for (int i = 0; i < 64; ++i) radii.push_back(0.01 * std::pow(2000.0, i / 63.0));

  std::printf("Cost of one R(r) evaluation, median of %d runs (alpha' = 0.9, g = 0, eta = 1.3; r in [0.01, 20] ell)\n",
              repetitions);
  const auto m = reduce(0.1, 0.9, 0.0, 1.3);
  std::vector<std::string> names;  // every row of the model registry, NAME+ss included
  for (const auto& e : model_registry()) names.push_back(e.name);
  std::vector<double> ns;
  double pbd_ns = 0;
  for (const auto& name : names) {
    const auto model = make_model(name);
    model->reflectance(m, 1.0);  // warm caches (quadrature order, mixture, surface albedo; exact: its profile)
    ns.push_back(median_ns_per_call([&](double r) { return model->reflectance(m, r); }, radii, repetitions));
    if (name == "pbd") pbd_ns = ns.back();
  }
  for (std::size_t k = 0; k < names.size(); ++k)
    std::printf("  %-16s %9.1f ns   %7.3f x pbd\n", names[k].c_str(), ns[k], ns[k] / pbd_ns);
  // exact builds its profile once per medium (then ~ns per radius): that cost on its own.
  const ExactTable& table = bundled_exact_table();
  std::vector<double> albedos;
  for (int i = 0; i < 64; ++i) albedos.push_back(0.5 + 0.007 * i);
  const double build_ns =
      median_ns_per_call([&](double a) { return ExactProfile(table, a, 0.3, 1.35).total(); }, albedos, repetitions);
  std::printf("  %-16s %9.1f ns   %7.3f x pbd   (one ExactProfile build, per medium)\n", "exact build", build_ns,
              build_ns / pbd_ns);

  std::printf("\nPhoton beam diffusion: ours vs pbrt's 100 + 100 midpoint samples (same process)\n");
  std::printf("  case                     pbrt ns   pbrt worst err   ours n  ours ns   ours worst err   speed-up\n");
  for (const auto& [alpha, g, eta] : {std::tuple{0.99, 0.0, 1.3}, std::tuple{0.9, 0.0, 1.0},
                                      std::tuple{0.999, 0.9, 1.4}, std::tuple{0.5, 0.0, 1.4}}) {
    const auto c = reduced_unit_extinction(alpha, g, eta);
    const auto b = improved_boundary(eta);
    const photon_beam_diffusion::Model model;
    const int n = model.samples(c);
    double pbrt_error = 0, our_error = 0;
    for (double r : radii) {
      const double reference = photon_beam_diffusion::reflectance(c, b, r, 1024);
      pbrt_error = std::max(pbrt_error, std::abs(pbrt_style_pbd(c, b, r) / reference - 1));
      our_error = std::max(our_error, std::abs(model.reflectance(c, r) / reference - 1));
    }
    const double pbrt_ns = median_ns_per_call([&](double r) { return pbrt_style_pbd(c, b, r); }, radii, repetitions);
    const double our_ns = median_ns_per_call([&](double r) { return model.reflectance(c, r); }, radii, repetitions);
    std::printf("  alpha %.3f g %.1f eta %.1f  %8.0f   %12.2e   %5d  %7.0f   %12.2e   %6.1fx\n", alpha, g, eta, pbrt_ns,
                pbrt_error, n, our_ns, our_error, pbrt_ns / our_ns);
  }
  return 0;
}
