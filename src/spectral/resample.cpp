#include "bssrdf/spectral/resample.hpp"

#include <algorithm>

#include "bssrdf/check.hpp"
#include "bssrdf/error.hpp"

namespace bssrdf::spectral {

double interpolate_linear(const std::vector<double>& x, const std::vector<double>& y, double at) {
  BSSRDF_CHECK(!x.empty() && x.size() == y.size() && at >= x.front() && at <= x.back());
  if (x.size() == 1) return y.front();
  const auto hi = std::min<std::size_t>(std::upper_bound(x.begin(), x.end(), at) - x.begin(), x.size() - 1);
  const std::size_t lo = hi - 1;
  const double f = (at - x[lo]) / (x[hi] - x[lo]);
  return y[lo] + f * (y[hi] - y[lo]);
}

Medium resample(const Medium& medium, const std::vector<double>& wavelength_nm) {
  if (!medium.spectral())
    throw InvalidInput("wavelengths: the medium has no wavelengths to resample (its channels are " +
                       medium.channel_names.front() + ", ...)");
  const auto& x = medium.wavelength_nm;
  Medium out;
  out.eta = medium.eta;
  out.wavelength_nm = wavelength_nm;
  out.channel_names = wavelength_channel_names(wavelength_nm);
  for (double nm : wavelength_nm) {
    if (!(nm >= x.front() && nm <= x.back()))
      throw InvalidInput("wavelengths", format_number(nm),
                         format_number(x.front()) + " to " + format_number(x.back()) + " nm (the medium's range)");
    out.sigma_a.push_back(interpolate_linear(x, medium.sigma_a, nm));
    out.sigma_s.push_back(interpolate_linear(x, medium.sigma_s, nm));
    out.g.push_back(interpolate_linear(x, medium.g, nm));
  }
  return out;
}

}  // namespace bssrdf::spectral
