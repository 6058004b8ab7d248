// The error a viewer sees: how differently a representation of a material's profile and the
// reference profile render two test patterns at a given pixel size, in 8-bit sRGB code values.
//
// Patterns (irradiance 1 per unit area, the image in exitance per unit entered flux):
//  - a shadow edge: the half-plane X > 0 lit. Exitance at x: E(x) = int int_{X' > 0} R(|p - p'|) dA'.
//  - a light line one pixel wide: the strip 0 < X < p lit (the edge minus the edge shifted by p).
// Each is box-filtered over square pixels of side p whose boundaries fall on the edge (pixel k
// covers k p <= x < (k+1) p; the image is uniform along y), for k = -K .. K-1 with K p >= the
// profile's extent (K <= kMaxPixelsEachSide). A pixel's linear value v, between 0 and the
// material's diffuse reflectance (its "lit albedo": a fully lit region shows it), is shown as the
// continuous sRGB code value 255 srgb(v) (IEC 61966-2-1 transfer function; not rounded, so
// differences below one code value are measured). The error is the largest |code difference| over
// both patterns, all pixels, a flat lit region (the albedo) and every colour channel: 1 means one
// 8-bit step somewhere in the image.
//
// Coarser pixels: in linear values an edge pixel k p wide is the mean of k pixels p wide, so the
// linear edge error at k p never exceeds the one at p (the line pattern, one pixel wide, is a
// different stimulus at each pixel size). In code values it can: a coarser pixel beside the edge
// is darker, and sRGB magnifies a linear difference in the dark (slope 12.92 x 255 at black). For
// pixels finer than the profile the code-value error can therefore grow with the pixel size
// (measured: tests/test_image_error.cpp); the advice holds for the pixel size it was asked for.
//
// Exactness: each annulus's light is spread evenly over its area, so a pixel's value is exactly
//   v_k = sum_i energy_i w_ik,   w_ik = the average over the pixel of the fraction of annulus i,
// centred at the pixel's points, that lies on the lit side,
// computed in closed form from the disc's area beyond a chord, A(r, s) = r^2 acos(s/r) - s sqrt(r^2 - s^2),
// and its antiderivative P(r, s) = s A(r, s) - (2/3) (r^2 - s^2)^(3/2). Both profiles use the same
// annuli, so binning changes only where within an annulus the light lands.
//
// Noise: a Monte Carlo reference has independent-ish annulus errors; the standard error of a pixel
// is sqrt(sum_i w_ik^2 stderr_i^2) (an upper bound: photons land in one annulus each, so the
// covariances are negative), shown in code values through the sRGB slope. reference_noise is the
// largest over pixels, patterns and channels (one standard error).
//
//   ImageErrorMeter meter(reference.edges, 0.1);          // 0.1 mm pixels
//   ImageError e = meter.error(reference_channels, candidate_channels);
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "bssrdf/image/annular_profile.hpp"

namespace bssrdf {

inline constexpr std::size_t kMaxPixelsEachSide = 4096;

// The sRGB transfer function (linear [0, 1], clamped, to encoded [0, 1]) and its slope.
double srgb_encode(double linear);
double srgb_slope(double linear);

struct ImageError {
  double error = 0;            // largest |code value difference| (8-bit sRGB, continuous)
  double linear_error = 0;     // largest |linear pixel difference| (fraction of white), same pixels
  double reference_noise = 0;  // one standard error of the reference's codes, largest over pixels
  std::string pattern;         // where the largest difference is: "flat", "edge" or "line"
  std::size_t channel = 0;
  double position = 0;  // centre of that pixel, mm from the edge (lit side > 0)
};

// The image of both patterns for one channel: linear pixel values, pixel k at index k + K, and the
// value of a flat lit region (the diffuse reflectance the representation shows).
struct PatternImage {
  std::vector<double> edge, line;
  std::vector<double> edge_stderr, line_stderr;
  double flat = 0;
};

class ImageErrorMeter {
 public:
  // `edges`: the annuli shared by every profile measured; `pixel`: side of a pixel, mm (> 0).
  ImageErrorMeter(std::vector<double> edges, double pixel);

  double pixel() const { return pixel_; }
  const std::vector<double>& edges() const { return edges_; }
  std::size_t pixels_each_side() const { return K_; }
  double pixel_centre(std::size_t index) const;  // mm

  PatternImage render(const AnnularProfile& profile) const;
  // A screen-space kernel of point taps (a separable pass, Jimenez et al. 2015): pixel k shows
  // albedo x sum_i weight_i I(x_k + offset_i), x_k the pixel's centre and I the irradiance image
  // read between pixel centres by linear interpolation (a bilinear texture fetch; the patterns are
  // uniform along y, so the vertical pass leaves them unchanged). Offsets in mm, weights summing to 1.
  PatternImage render_taps(const std::vector<double>& offset, const std::vector<double>& weight, double albedo) const;
  // One profile per channel in each; the reference's standard errors give the noise.
  ImageError error(const std::vector<AnnularProfile>& reference, const std::vector<AnnularProfile>& candidate) const;
  // The same from rendered images (render the reference once when judging many candidates).
  ImageError error(const std::vector<PatternImage>& reference, const std::vector<PatternImage>& candidate) const;

 private:
  std::vector<double> edges_;
  double pixel_ = 0;
  std::size_t K_ = 0;
  std::vector<std::vector<double>> weight_;  // [pixel][annulus - first_[pixel]], edge pattern
  std::vector<std::size_t> first_;           // [pixel]: annuli before it are wholly on one side
  double weight(std::size_t pixel, std::size_t annulus) const;
};

}  // namespace bssrdf
