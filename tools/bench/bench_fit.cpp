// Fitting speed (medians): a 3-channel profile fit with 64 samples per channel for each
// differentiable model, and the albedo inversion for 1000 spectral bins.
//
//   bench_fit [repetitions=11]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "bssrdf/fit/inverse_fits.hpp"
#include "bssrdf/fit/profile_fit.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/profile.hpp"

using namespace bssrdf;

namespace {
template <class F>
double median_ms(F&& f, int repetitions) {
  std::vector<double> t;
  for (int i = 0; i < repetitions; ++i) {
    const auto start = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  std::nth_element(t.begin(), t.begin() + repetitions / 2, t.end());
  return t[repetitions / 2];
}
}  // namespace

int main(int argc, char** argv) {
  const int repetitions = argc > 1 ? std::max(1, std::atoi(argv[1])) : 11;
  const double sigma_a[] = {0.032, 0.17, 0.48}, sigma_s_prime[] = {0.74, 0.88, 1.01};  // Jensen's Skin1
  std::printf("Profile fit, 3 channels x 64 log-spaced radii (Skin1, eta 1.3), median of %d:\n", repetitions);
  for (const char* name : {"dipole", "better-dipole", "pbd", "quantized", "better-dipole+ss", "burley"}) {
    const auto model = make_model(name);
    MeasuredProfile data;
    data.file = "synthetic";
    data.radius = log_spaced(0.05, 10.0, 64);
    for (int c = 0; c < 3; ++c) {
      MeasuredProfile::Channel ch{std::string(1, "RGB"[c]), {}, {}};
      for (double r : data.radius)
        ch.value.push_back(model->reflectance(reduce(sigma_a[c], sigma_s_prime[c], 0.0, 1.3), r));
      data.channels.push_back(ch);
    }
    ProfileFitOptions options;
    options.model = name;
    int iterations = 0;
    const double ms = median_ms([&] { iterations = fit_profile(data, options).iterations; }, repetitions);
    std::printf("  %-17s %8.2f ms  (%d iterations)\n", name, ms, iterations);
  }
  std::printf("\nAlbedo inversion (total + mfp -> sigma_a, sigma_s'), 1000 spectral bins, median of %d:\n",
              repetitions);
  for (const char* name : {"dipole", "better-dipole", "quantized", "pbd"}) {
    const int bins = std::string(name) == "pbd" || std::string(name) == "quantized" ? 20 : 1000;
    const double ms = median_ms(
        [&] {
          for (int i = 0; i < bins; ++i)
            invert_albedo(name, 0.05 + 0.85 * i / (bins - 1.0), 1.0, DistanceConvention::mfp, 1.3);
        },
        std::max(1, repetitions / (bins < 1000 ? 4 : 1)));
    std::printf("  %-17s %8.2f ms per 1000 bins%s\n", name, ms * 1000.0 / bins,
                bins < 1000 ? " (extrapolated from 20 bins)" : "");
  }
  return 0;
}
