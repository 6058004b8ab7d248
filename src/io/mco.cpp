#include "bssrdf/io/mco.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "bssrdf/error.hpp"

namespace bssrdf {
namespace {
constexpr double kCmPerMm = 0.1;

std::string printf_string(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

std::string g14(double v) { return printf_string("%-14.6G", v); }  // MCML's RAT and InParm numbers
std::string e12(double v) { return printf_string("%12.4E", v); }   // MCML's arrays

std::string one_a_line(const std::string& label, const std::vector<double>& values) {
  std::string out = label + "\n";
  for (double v : values) out += e12(v) + "\n";
  return out + "\n";
}

// MCML's 2D arrays: row-major, five numbers a line.
std::string five_a_line(const std::vector<std::string>& header, const std::vector<double>& values) {
  std::string out;
  for (const auto& line : header) out += line + "\n";
  for (std::size_t i = 0; i < values.size(); ++i) out += e12(values[i]) + " " + ((i + 1) % 5 == 0 ? "\n" : "");
  return out + "\n\n";
}
}  // namespace

std::string format_mco(const MonteCarloResult& result, const std::string& output_name, int na) {
  if (result.channels.size() != 1)
    throw InvalidInput("mco: " + std::to_string(result.channels.size()) + " channels; an MCML file holds one");
  if (result.options.spacing != BinSpacing::linear)
    throw InvalidInput("mco: log-spaced radial bins; MCML's Rd_r needs linear bins (--spacing linear)");
  if (na < 1) throw InvalidInput("mco: na", std::to_string(na), ">= 1");
  const auto& c = result.channels.front();
  const auto& stack = result.stack;
  const std::size_t nr = result.bin_inner.size(), nz = c.absorbed_by_depth.size();
  const double dr = result.bin_outer.front() - result.bin_inner.front();  // mm
  const double dz = nz ? result.depth_outer.front() - result.depth_inner.front() : 0;
  const double da = std::numbers::pi / (2 * na);
  const double per_cm2 = 1 / (kCmPerMm * kCmPerMm), per_cm = 1 / kCmPerMm;

  // Radial arrays in 1/cm^2, with the light beyond r_max in the last bin (MCML clamps the index).
  const auto radial = [&](const std::vector<double>& binned, double beyond) {
    std::vector<double> out(nr, 0.0);
    for (std::size_t i = 0; i < binned.size() && i < nr; ++i) out[i] = binned[i] * per_cm2;
    if (nr && !binned.empty()) out[nr - 1] += beyond / (2 * std::numbers::pi * (nr - 0.5) * dr * dr) * per_cm2;
    return out;
  };
  const auto Rd_r = radial(c.reflectance, c.reflectance_beyond);
  const auto Tt_r = radial(c.transmittance, c.transmittance_beyond);

  // A_z (1/cm), absorption below the grid in the last bin; A_l by the layer of each bin's centre.
  std::vector<double> A_z(nz, 0.0), A_l(stack.layers.size(), 0.0);
  double binned = 0;
  for (std::size_t i = 0; i < nz; ++i) A_z[i] = c.absorbed_by_depth[i], binned += c.absorbed_by_depth[i] * dz;
  if (nz) A_z[nz - 1] += (c.absorbed.value - binned) / dz;
  for (std::size_t i = 0; i < nz; ++i) {
    std::size_t layer = 0;
    for (double top = 0; layer + 1 < stack.layers.size() && (i + 0.5) * dz >= top + stack.layers[layer].thickness;)
      top += stack.layers[layer++].thickness;
    A_l[layer] += A_z[i] * dz;
    A_z[i] *= per_cm;
  }

  // Angle-resolved arrays: only one angle bin is known (the whole hemisphere), with MCML's
  // scaling: Rd_a by the solid angle 2 pi sin(a) da, Rd_ra by 4 pi^2 dr^2 sin(da/2) (ir+0.5) sin(2a).
  const double hemisphere_a = 2 * std::numbers::pi * da * std::sin(0.5 * da);
  std::vector<double> Rd_a(na, 0.0), Tt_a(na, 0.0), Rd_ra(nr * na, 0.0), Tt_ra(nr * na, 0.0);
  if (na == 1) {
    Rd_a[0] = c.diffuse_reflectance.value / hemisphere_a;
    Tt_a[0] = c.total_transmittance.value / hemisphere_a;
    for (std::size_t i = 0; i < nr; ++i) {
      // weight in annulus i = R(r_i) 2 pi (i + 0.5) dr^2; the ra bin divides it by MCML's scale.
      const double ra_over_r = 2 * std::numbers::pi /
                               (4 * std::numbers::pi * std::numbers::pi * std::sin(0.5 * da) * std::sin(2 * 0.5 * da));
      Rd_ra[i] = Rd_r[i] * ra_over_r;
      Tt_ra[i] = Tt_r[i] * ra_over_r;
    }
  }

  const double cm = kCmPerMm;
  std::string out =
      "A1 \t# Version number of the file format.\n\n"
      "####\n# Data categories include: \n# InParm, RAT, \n# A_l, A_z, Rd_r, Rd_a, Tt_r, Tt_a, \n# A_rz, Rd_ra, Tt_ra "
      "\n####\n\n"
      "# Written by bssrdf " BSSRDF_VERSION " (reference --mci): " +
      std::to_string(result.options.photons) + " photons in " + printf_string("%.3g", result.seconds) + " s, seed " +
      std::to_string(result.options.seed) + "\n\n";
  out += "InParm \t\t\t# Input parameters. cm is used.\n";
  out += output_name + " \tA\t\t# output file name, ASCII.\n";
  out += std::to_string(result.options.photons) + " \t\t\t# No. of photons\n";
  out += printf_string("%G", dz * cm) + "\t" + printf_string("%G", dr * cm) + "\t\t# dz, dr [cm]\n";
  out += std::to_string(nz) + "\t" + std::to_string(nr) + "\t" + std::to_string(na) + "\t# No. of dz, dr, da.\n\n";
  out += std::to_string(stack.layers.size()) + "\t\t\t\t\t# Number of layers\n";
  out += "#n\tmua\tmus\tg\td\t# One line for each layer\n";
  out += printf_string("%G", stack.ambient_above) + "\t\t\t\t\t# n for medium above\n";
  for (std::size_t i = 0; i < stack.layers.size(); ++i) {
    const auto& l = stack.layers[i];
    out += printf_string("%G", l.n) + "\t" + printf_string("%G", l.sigma_a[0] * per_cm) + "\t" +
           printf_string("%G", l.sigma_s[0] * per_cm) + "\t" + printf_string("%G", l.g[0]) + "\t" +
           (std::isfinite(l.thickness) ? printf_string("%G", l.thickness * cm) : std::string("1E+09")) + "\t# layer " +
           std::to_string(i + 1) + "\n";
  }
  out += printf_string("%G", stack.ambient_below) + "\t\t\t\t\t# n for medium below\n\n";
  out += "RAT #Reflectance, absorption, transmission. \n";
  out += g14(c.specular_reflectance) + " \t#Specular reflectance [-]\n";
  out += g14(c.diffuse_reflectance.value) + " \t#Diffuse reflectance [-]\n";
  out += g14(c.absorbed.value) + " \t#Absorbed fraction [-]\n";
  out += g14(c.total_transmittance.value) + " \t#Transmittance [-]\n\n";
  out += "A_l #Absorption as a function of layer. [-]\n";
  for (double v : A_l) out += printf_string("%12.4G", v) + "\n";
  out += "\n";
  const std::string not_depth = nz ? "" : "# A_z: depth bins were off: zeros\n";
  const std::string angles = na == 1 ? "# (na = 1: one angle bin, the whole hemisphere, from the totals)\n"
                                     : "# not tallied by bssrdf (no exit angles): zeros\n";
  out += not_depth + one_a_line("A_z #A[0], [1],..A[nz-1]. [1/cm]", A_z);
  out += one_a_line("Rd_r #Rd[0], [1],..Rd[nr-1]. [1/cm2]", Rd_r);
  out += angles + one_a_line("Rd_a #Rd[0], [1],..Rd[na-1]. [sr-1]", Rd_a);
  out += (c.transmittance.empty() ? "# semi-infinite: no transmission\n" : "") +
         one_a_line("Tt_r #Tt[0], [1],..Tt[nr-1]. [1/cm2]", Tt_r);
  out += angles + one_a_line("Tt_a #Tt[0], [1],..Tt[na-1]. [sr-1]", Tt_a);
  out += "# A_rz: not tallied by bssrdf (absorption is binned by depth only): zeros\n" +
         five_a_line({"# A[r][z]. [1/cm3]", "# A[0][0], [0][1],..[0][nz-1]", "# A[1][0], [1][1],..[1][nz-1]", "# ...",
                      "# A[nr-1][0], [nr-1][1],..[nr-1][nz-1]", "A_rz"},
                     std::vector<double>(nr * nz, 0.0));
  out += angles +
         five_a_line({"# Rd[r][angle]. [1/(cm2sr)].", "# Rd[0][0], [0][1],..[0][na-1]",
                      "# Rd[1][0], [1][1],..[1][na-1]", "# ...", "# Rd[nr-1][0], [nr-1][1],..[nr-1][na-1]", "Rd_ra"},
                     Rd_ra);
  out += angles +
         five_a_line({"# Tt[r][angle]. [1/(cm2sr)].", "# Tt[0][0], [0][1],..[0][na-1]",
                      "# Tt[1][0], [1][1],..[1][na-1]", "# ...", "# Tt[nr-1][0], [nr-1][1],..[nr-1][na-1]", "Tt_ra"},
                     Tt_ra);
  return out;
}

}  // namespace bssrdf
