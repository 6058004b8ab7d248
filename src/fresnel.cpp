#include "bssrdf/fresnel.hpp"

namespace bssrdf {

const ImprovedBoundary<double>& cached_improved_boundary(double eta) {
  thread_local double cached_eta = -1;
  thread_local ImprovedBoundary<double> cached{};
  if (eta != cached_eta) {
    cached = improved_boundary(eta);
    cached_eta = eta;
  }
  return cached;
}

}  // namespace bssrdf
