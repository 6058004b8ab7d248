// Colour from spectra: a spectrum sampled at any wavelengths becomes CIE XYZ under an illuminant, and linear RGB in
// an output space (linear sRGB/Rec.709, ACEScg, Rec.2020), by
//   C_c = sum over 1 nm steps of s(lambda) S(lambda) cbar_c(lambda) / sum of S(lambda) ybar(lambda)
// (CIE 15:2004 section 7: the 1 nm summation of the CIE's own tables), so a perfect white reflector has Y = 1. The
// spectrum s is the sampled values joined linearly and held at the end values beyond the first and last samples.
// Every colour is linear in the samples: ColourIntegrator holds the weight of each sample in each output channel,
// so integrating per radius and then totalling equals the colour of the total (the totals check of docs/spectral.md).
// XYZ goes to RGB through the space's primaries and white (SMPTE RP 177 derivation), with a Bradford chromatic
// adaptation from the illuminant's white to the space's white (so a white reflector is (1, 1, 1) under every
// illuminant).
//
//   ColourIntegrator colour({400, 450, ..., 700}, {Illuminant::d65, ColourSpace::srgb});
//   auto rgb = colour.rgb(reflectance);   // linear sRGB
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "bssrdf/spectral/cie.hpp"

namespace bssrdf::spectral {

enum class ColourSpace { srgb, acescg, rec2020 };
std::string_view to_string(ColourSpace space);  // "linear sRGB", "ACEScg", "Rec.2020"
std::string_view key(ColourSpace space);        // "srgb", "acescg", "rec2020"
ColourSpace parse_colour_space(const std::string& text, const std::string& field = "colour");

struct ColourSettings {
  Illuminant illuminant = Illuminant::d65;
  ColourSpace space = ColourSpace::srgb;
};

using Vec3 = std::array<double, 3>;
using Mat3 = std::array<Vec3, 3>;

// The illuminant's white, XYZ with Y = 1 (1 nm summation over the observer's range).
Vec3 white_xyz(Illuminant illuminant);
// XYZ (any white) -> linear RGB of `space`: the space's matrix after a Bradford adaptation from `white`.
Mat3 xyz_to_rgb_matrix(ColourSpace space, const Vec3& white);
// The space's own matrix (its primaries and white, no adaptation).
Mat3 xyz_to_rgb_matrix(ColourSpace space);
Vec3 operator*(const Mat3& m, const Vec3& v);
Mat3 inverse(const Mat3& m);  // InternalError when singular

// CIE 1976 L*a*b* relative to `white` (Y = 1), and the CIEDE2000 difference (Sharma, Wu and Dalal 2005, with
// kL = kC = kH = 1).
Vec3 xyz_to_lab(const Vec3& xyz, const Vec3& white);
double ciede2000(const Vec3& lab1, const Vec3& lab2);
// IEC 61966-2-1 sRGB transfer: encoded (display) value in [0, 1] -> linear, and back.
double srgb_to_linear(double encoded);
double linear_to_srgb(double linear);

class ColourIntegrator {
 public:
  // Wavelengths in nm, strictly increasing (InvalidInput naming "wavelengths" otherwise), at least one.
  ColourIntegrator(std::vector<double> wavelength_nm, ColourSettings settings);
  const std::vector<double>& wavelengths() const { return wavelength_nm_; }
  const ColourSettings& settings() const { return settings_; }
  // The weight of sample i in X, Y, Z, and in the output space's R, G, B.
  const std::vector<Vec3>& xyz_weights() const { return xyz_weight_; }
  const std::vector<Vec3>& rgb_weights() const { return rgb_weight_; }
  Vec3 xyz(const std::vector<double>& samples) const;
  Vec3 rgb(const std::vector<double>& samples) const;
  // L*a*b* of the spectrum under the illuminant (its own white).
  Vec3 lab(const std::vector<double>& samples) const;

 private:
  std::vector<double> wavelength_nm_;
  ColourSettings settings_;
  Vec3 white_;
  std::vector<Vec3> xyz_weight_, rgb_weight_;
};

}  // namespace bssrdf::spectral
