// Diagonal boundaries of interfaces and slides; see boundary.hpp.
#include "boundary.hpp"

#include <cmath>

#include "bssrdf/fresnel.hpp"

namespace bssrdf::adding_doubling {

namespace {

struct Element {
  double r_top, r_bottom, t;
};

// `upper` on top of `lower`, one angle: the scalar adding equations.
Element add(const Element& upper, const Element& lower) {
  const double bounce = upper.r_bottom * lower.r_top;
  if (bounce >= 1) return {upper.r_top, lower.r_bottom, 0};  // trapped between two total reflections
  const double k = 1 / (1 - bounce);
  return {upper.r_top + upper.t * upper.t * lower.r_top * k, lower.r_bottom + lower.t * lower.t * upper.r_bottom * k,
          upper.t * lower.t * k};
}

}  // namespace

Boundary make_boundary(const Angles& angles, double n, const std::vector<ClearLayer>& media) {
  Boundary out;
  for (double mu : angles.mu) {
    const double invariant = n * std::sqrt(std::max(0.0, 1 - mu * mu));  // n sin(theta), Snell
    auto cosine_in = [&](double index) {  // negative: the angle does not exist in that medium
      const double s = invariant / index;
      return s >= 1 ? -1.0 : std::sqrt(1 - s * s);
    };
    Element total{0, 0, 1};
    for (std::size_t k = 0; k + 1 < media.size(); ++k) {
      const double a = media[k].n, b = media[k + 1].n;
      const double ca = cosine_in(a), cb = cosine_in(b);
      Element interface { 1, 1, 0 };
      if (ca > 0 && cb > 0) {
        const double r = fresnel_reflectance(ca, a / b);
        interface = {r, r, 1 - r};
      }
      total = add(total, interface);
      if (k + 2 < media.size() && cb > 0) {  // the clear layer below this interface
        const double e = std::exp(-media[k + 1].sigma_a * media[k + 1].thickness / cb);
        total = add(total, {0, 0, e});
      }
    }
    out.r_top.push_back(total.r_top);
    out.r_bottom.push_back(total.r_bottom);
    out.t.push_back(total.t);
  }
  return out;
}

}  // namespace bssrdf::adding_doubling
