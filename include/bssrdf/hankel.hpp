// Zero-order Hankel transform: the 2D Fourier transform of a radially symmetric function, used to
// combine layers (models/layered.hpp), where adding layers is a product of spectra.
//
//   H[f](q) = int_0^inf f(x) J0(q x) x dx
//   F(k) = 2 pi H[R](k)          (spectrum of a radial profile R(r); F(0) = int 2 pi r R dr)
//   R(r) = H[F](r) / (2 pi)       (and back)
//
// Evaluated by quadrature between consecutive zeros of J0(q x) (adaptive Gauss-Kronrod on each
// half-wave), summed until the half-waves stop contributing; accurate to ~1e-10 of the largest
// half-wave for functions that decay (exponentially or faster than 1/x^2). The round trip
// R -> F -> R is measured in tests/test_layered.cpp.
#pragma once

#include <functional>

namespace bssrdf {

// H[f](q) for q >= 0. `scale`: a length over which f varies (e.g. ell, or 1/k_scale for a
// spectrum), used only at q = 0.
double hankel_transform(const std::function<double(double)>& f, double q, double scale, double rel_tol = 1e-10);

// The m-th positive zero of J0 (m >= 1), to about 1e-10 relative.
double bessel_j0_zero(int m);

}  // namespace bssrdf
