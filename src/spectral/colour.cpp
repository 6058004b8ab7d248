#include "bssrdf/spectral/colour.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>

#include "bssrdf/check.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/text.hpp"

namespace bssrdf::spectral {
namespace {

Mat3 multiply(const Mat3& a, const Mat3& b) {
  Mat3 c{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) c[i][j] += a[i][k] * b[k][j];
  return c;
}

}  // namespace

Mat3 inverse(const Mat3& m) {
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  BSSRDF_CHECK(det != 0);
  Mat3 r;
  r[0] = {(m[1][1] * m[2][2] - m[1][2] * m[2][1]) / det, (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det,
          (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det};
  r[1] = {(m[1][2] * m[2][0] - m[1][0] * m[2][2]) / det, (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det,
          (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det};
  r[2] = {(m[1][0] * m[2][1] - m[1][1] * m[2][0]) / det, (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det,
          (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det};
  return r;
}

namespace {

Vec3 xy_to_xyz(double x, double y) { return {x / y, 1, (1 - x - y) / y}; }

// Primaries r, g, b and white as CIE 1931 xy: ITU-R BT.709 (sRGB), ACES AP1 (SMPTE ST 2065-1 / S-2014-004, white
// 0.32168, 0.33767), ITU-R BT.2020.
struct Primaries {
  double rx, ry, gx, gy, bx, by, wx, wy;
};
Primaries primaries(ColourSpace space) {
  switch (space) {
    case ColourSpace::srgb:
      return {0.64, 0.33, 0.30, 0.60, 0.15, 0.06, 0.3127, 0.3290};
    case ColourSpace::acescg:
      return {0.713, 0.293, 0.165, 0.830, 0.128, 0.044, 0.32168, 0.33767};
    case ColourSpace::rec2020:
      return {0.708, 0.292, 0.170, 0.797, 0.131, 0.046, 0.3127, 0.3290};
  }
  BSSRDF_CHECK(false);
  return {};
}

// Bradford cone response (Lam 1985; as in CIE 159 and ICC.1 Annex E).
constexpr Mat3 kBradford{{{0.8951, 0.2664, -0.1614}, {-0.7502, 1.7135, 0.0367}, {0.0389, -0.0685, 1.0296}}};

Mat3 bradford(const Vec3& from, const Vec3& to) {
  const Vec3 a = kBradford * from, b = kBradford * to;
  Mat3 scale{};
  for (int i = 0; i < 3; ++i) scale[i][i] = b[i] / a[i];
  return multiply(inverse(kBradford), multiply(scale, kBradford));
}

double lab_f(double t) {
  constexpr double d = 6.0 / 29;
  return t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29;
}

}  // namespace

Vec3 operator*(const Mat3& m, const Vec3& v) {
  return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2], m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
          m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

std::string_view to_string(ColourSpace space) {
  switch (space) {
    case ColourSpace::srgb:
      return "linear sRGB";
    case ColourSpace::acescg:
      return "ACEScg";
    case ColourSpace::rec2020:
      return "Rec.2020";
  }
  return "?";
}

std::string_view key(ColourSpace space) {
  switch (space) {
    case ColourSpace::srgb:
      return "srgb";
    case ColourSpace::acescg:
      return "acescg";
    case ColourSpace::rec2020:
      return "rec2020";
  }
  return "?";
}

ColourSpace parse_colour_space(const std::string& text, const std::string& field) {
  const std::string lower = bssrdf::lower(text);
  for (auto space : {ColourSpace::srgb, ColourSpace::acescg, ColourSpace::rec2020})
    if (lower == key(space)) return space;
  throw InvalidInput(field, "'" + text + "'", "srgb, acescg or rec2020");
}

Vec3 white_xyz(Illuminant illuminant) {
  Vec3 xyz{};
  for (int nm = static_cast<int>(kObserverMin); nm <= static_cast<int>(kObserverMax); ++nm) {
    const double s = illuminant_power(illuminant, nm);
    const auto c = observer(nm);
    for (int k = 0; k < 3; ++k) xyz[k] += s * c[k];
  }
  return {xyz[0] / xyz[1], 1, xyz[2] / xyz[1]};
}

Mat3 xyz_to_rgb_matrix(ColourSpace space) {
  const auto p = primaries(space);
  const Vec3 r = xy_to_xyz(p.rx, p.ry), g = xy_to_xyz(p.gx, p.gy), b = xy_to_xyz(p.bx, p.by);
  const Mat3 m{{{r[0], g[0], b[0]}, {r[1], g[1], b[1]}, {r[2], g[2], b[2]}}};
  const Vec3 s = inverse(m) * xy_to_xyz(p.wx, p.wy);
  Mat3 rgb_to_xyz = m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) rgb_to_xyz[i][j] *= s[j];
  return inverse(rgb_to_xyz);
}

Mat3 xyz_to_rgb_matrix(ColourSpace space, const Vec3& white) {
  const auto p = primaries(space);
  return multiply(xyz_to_rgb_matrix(space), bradford(white, xy_to_xyz(p.wx, p.wy)));
}

Vec3 xyz_to_lab(const Vec3& xyz, const Vec3& white) {
  const double fx = lab_f(xyz[0] / white[0]), fy = lab_f(xyz[1] / white[1]), fz = lab_f(xyz[2] / white[2]);
  return {116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)};
}

double ciede2000(const Vec3& lab1, const Vec3& lab2) {
  const auto deg = [](double rad) { return rad * 180 / std::numbers::pi; };
  const auto rad = [](double degrees) { return degrees * std::numbers::pi / 180; };
  const double c1 = std::hypot(lab1[1], lab1[2]), c2 = std::hypot(lab2[1], lab2[2]);
  const double c_mean7 = std::pow((c1 + c2) / 2, 7);
  const double G = 0.5 * (1 - std::sqrt(c_mean7 / (c_mean7 + std::pow(25.0, 7))));
  const double a1 = (1 + G) * lab1[1], a2 = (1 + G) * lab2[1];
  const double C1 = std::hypot(a1, lab1[2]), C2 = std::hypot(a2, lab2[2]);
  const auto hue = [&](double b, double a) {
    if (a == 0 && b == 0) return 0.0;
    const double h = deg(std::atan2(b, a));
    return h < 0 ? h + 360 : h;
  };
  const double h1 = hue(lab1[2], a1), h2 = hue(lab2[2], a2);
  const double dL = lab2[0] - lab1[0], dC = C2 - C1;
  double dh = 0;
  if (C1 * C2 != 0) {
    dh = h2 - h1;
    if (dh > 180) dh -= 360;
    if (dh < -180) dh += 360;
  }
  const double dH = 2 * std::sqrt(C1 * C2) * std::sin(rad(dh / 2));
  const double L_mean = (lab1[0] + lab2[0]) / 2, C_mean = (C1 + C2) / 2;
  double h_mean = h1 + h2;
  if (C1 * C2 != 0) {
    if (std::abs(h1 - h2) <= 180)
      h_mean = (h1 + h2) / 2;
    else
      h_mean = h1 + h2 < 360 ? (h1 + h2 + 360) / 2 : (h1 + h2 - 360) / 2;
  }
  const double T = 1 - 0.17 * std::cos(rad(h_mean - 30)) + 0.24 * std::cos(rad(2 * h_mean)) +
                   0.32 * std::cos(rad(3 * h_mean + 6)) - 0.20 * std::cos(rad(4 * h_mean - 63));
  const double d_theta = 30 * std::exp(-std::pow((h_mean - 275) / 25, 2));
  const double C_mean7 = std::pow(C_mean, 7);
  const double RC = 2 * std::sqrt(C_mean7 / (C_mean7 + std::pow(25.0, 7)));
  const double l50 = (L_mean - 50) * (L_mean - 50);
  const double SL = 1 + 0.015 * l50 / std::sqrt(20 + l50), SC = 1 + 0.045 * C_mean, SH = 1 + 0.015 * C_mean * T;
  const double RT = -std::sin(rad(2 * d_theta)) * RC;
  const double l = dL / SL, c = dC / SC, h = dH / SH;
  return std::sqrt(l * l + c * c + h * h + RT * c * h);
}

double srgb_to_linear(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }
double linear_to_srgb(double v) { return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055; }

ColourIntegrator::ColourIntegrator(std::vector<double> wavelength_nm, ColourSettings settings)
    : wavelength_nm_(std::move(wavelength_nm)), settings_(settings), white_(white_xyz(settings.illuminant)) {
  const std::size_t n = wavelength_nm_.size();
  if (n == 0) throw InvalidInput("wavelengths", "(none)", "at least one wavelength");
  for (std::size_t i = 0; i < n; ++i) {
    if (!(std::isfinite(wavelength_nm_[i]) && wavelength_nm_[i] > 0))
      throw InvalidInput("wavelengths", format_number(wavelength_nm_[i]), "> 0 nm and finite");
    if (i > 0 && !(wavelength_nm_[i] > wavelength_nm_[i - 1]))
      throw InvalidInput("wavelengths", format_number(wavelength_nm_[i]),
                         "strictly increasing (after " + format_number(wavelength_nm_[i - 1]) + ")");
  }
  xyz_weight_.assign(n, Vec3{});
  double norm = 0;
  for (int nm = static_cast<int>(kObserverMin); nm <= static_cast<int>(kObserverMax); ++nm) {
    const double s = illuminant_power(settings_.illuminant, nm);
    const auto c = observer(nm);
    norm += s * c[1];
    // The hat functions of linear interpolation, held constant beyond the ends.
    const auto upper = std::upper_bound(wavelength_nm_.begin(), wavelength_nm_.end(), double(nm));
    std::size_t i0, i1;
    double f;
    if (upper == wavelength_nm_.begin()) {
      i0 = i1 = 0, f = 0;
    } else if (upper == wavelength_nm_.end()) {
      i0 = i1 = n - 1, f = 0;
    } else {
      i1 = static_cast<std::size_t>(upper - wavelength_nm_.begin()), i0 = i1 - 1;
      f = (nm - wavelength_nm_[i0]) / (wavelength_nm_[i1] - wavelength_nm_[i0]);
    }
    for (int k = 0; k < 3; ++k) {
      xyz_weight_[i0][k] += (1 - f) * s * c[k];
      xyz_weight_[i1][k] += f * s * c[k];
    }
  }
  const Mat3 to_rgb = xyz_to_rgb_matrix(settings_.space, white_);
  rgb_weight_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (auto& w : xyz_weight_[i]) w /= norm;
    rgb_weight_[i] = to_rgb * xyz_weight_[i];
  }
}

Vec3 ColourIntegrator::xyz(const std::vector<double>& samples) const {
  BSSRDF_CHECK(samples.size() == xyz_weight_.size());
  Vec3 out{};
  for (std::size_t i = 0; i < samples.size(); ++i)
    for (int k = 0; k < 3; ++k) out[k] += xyz_weight_[i][k] * samples[i];
  return out;
}

Vec3 ColourIntegrator::rgb(const std::vector<double>& samples) const {
  BSSRDF_CHECK(samples.size() == rgb_weight_.size());
  Vec3 out{};
  for (std::size_t i = 0; i < samples.size(); ++i)
    for (int k = 0; k < 3; ++k) out[k] += rgb_weight_[i][k] * samples[i];
  return out;
}

Vec3 ColourIntegrator::lab(const std::vector<double>& samples) const { return xyz_to_lab(xyz(samples), white_); }

}  // namespace bssrdf::spectral
