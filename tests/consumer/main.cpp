// Uses the installed library: the better dipole's total reflectance of Jensen et al.'s Skin1 red
// channel (sigma_a 0.032/mm, sigma_s' 0.74/mm, eta 1.3), printed for the install test to check.
#include <bssrdf/medium.hpp>
#include <bssrdf/model.hpp>
#include <bssrdf/model_registry.hpp>
#include <cstdio>

#ifdef BSSRDF_VERSION
#error "the version define leaked to a consumer"
#endif

int main() {
  bssrdf::Medium medium;
  medium.sigma_a = {0.032};
  medium.sigma_s = {0.74};
  medium.g = {0.0};
  medium.eta = 1.3;
  medium.channel_names = {"R"};
  const auto model = bssrdf::make_model("better-dipole");
  std::printf("%.6f\n", model->total_reflectance(medium.reduced(0)));
  return 0;
}
