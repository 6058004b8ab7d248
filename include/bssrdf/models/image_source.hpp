// The extrapolated boundary, one convention for every diffusion model here (dipole, better dipole,
// photon beam diffusion, quantized diffusion, multipole, layered): the fluence is taken to vanish at
// the extrapolation distance z_b = 2 A D above the surface (Farrell, Patterson & Wilson 1992;
// Jensen et al. 2001, Eq. 6; d'Eon 2012 with D = D_G), and a source at depth z (> 0, into the medium)
// has a negative image mirrored through that plane, at depth z_v = -(z + 2 z_b) (< 0: above the
// surface). The exitance kernels of point_source.hpp are odd in z, so a model writes
// R = flux(z) - flux(z_v) (and fluence(z) - fluence(z_v)) with the image's own sign.
//
//   const T z_b = extrapolation_distance(A, m.D);   // 2 A D
//   const T z_v = image_depth(m.ell, z_b);           // -(ell + 4 A D)
#pragma once

namespace bssrdf {

template <class T>
T extrapolation_distance(T A, T D) {
  return T(2) * A * D;
}

template <class T>
T image_depth(T z, T extrapolation) {
  return -(z + T(2) * extrapolation);
}

}  // namespace bssrdf
