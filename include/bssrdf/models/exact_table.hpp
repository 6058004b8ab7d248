// The tabulated radiative-transfer solution behind the `exact` model: R(r) of a semi-infinite
// Henyey-Greenstein medium under a normally incident pencil beam, smooth boundary of relative
// index eta, per unit entered flux, on a grid of (alpha', g, eta) and radii in transport mean free
// paths. Built by tools/exact_table/generate_exact_table from the project's Monte Carlo (multiple
// scattering), the exact single-scattering integral and adding-doubling totals; the file format and
// the provenance are described in data/exact/README.md.
//
//   const ExactTable& table = bundled_exact_table();   // loaded once, on first use
//   float ln_y = table.ln_y[table.index(e, g, a, k)];  // y = 2 pi r^2 R(r), r = radius(k)
//
// Values are stored as ln y with y = 2 pi r^2 R(r) = dE/d ln r (dimensionless, lengths in
// transport mfp): smooth, positive, of modest range, and interpolating its logarithm keeps the
// exponential far tails exact between albedos.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "bssrdf/huge_page_allocator.hpp"

namespace bssrdf {

struct ExactTable {
  std::vector<double> albedo_prime;  // reduced albedo nodes, increasing
  std::vector<double> g;             // anisotropy nodes, increasing
  std::vector<double> eta;           // relative index nodes, increasing
  double ln_r0 = 0;                  // ln of the first radius (transport mfp)
  double d_ln_r = 0;                 // radius step in ln r
  std::size_t radii = 0;

  // The two arrays of a value per node and radius (1.8 MB in all) fill huge pages: loading them is
  // then one page fault per 2 MB (huge_page_allocator.hpp).
  template <class T>
  using NodeArray = std::vector<T, HugePageAllocator<T>>;
  // [eta][g][albedo][radius]
  NodeArray<float> ln_y;
  // Relative standard error of y, in units of 1e-4; kExtrapolated where the Monte Carlo had too
  // few photons and the value continues the measured profile (near field below the multiple-
  // scattering onset, far tail beyond the well-measured radii). Empty unless read with
  // TableErrors::read (the model does not use it).
  NodeArray<std::uint16_t> relative_error;
  static constexpr std::uint16_t kExtrapolated = 65535;
  // [eta][g][albedo]: total diffuse reflectance per unit entered flux (adding-doubling).
  std::vector<double> total;
  // Version 2: the totals again on a finer eta axis (the same ends; every eta node among them),
  // [total_eta][g][albedo]. The total bends sharply just above eta = 1, where total internal
  // reflection sets in, and the coarse eta nodes missed it by up to 0.5 % (eta 1.02). Empty in a
  // version 1 file: the totals above serve.
  std::vector<double> total_eta;
  std::vector<double> fine_total;

  std::string provenance;  // JSON: photons, seeds, generator version, run time, checks

  // Derived by prepare() (read_exact_table calls it): ln of each total, for the interpolation.
  std::vector<double> ln_total;  // ln of fine_total, or of total without it
  void prepare() {
    validate();
    ln_total.clear();
    for (double t : total_eta.empty() ? total : fine_total) ln_total.push_back(std::log(t));
  }
  // The eta axis of ln_total (node(e, g, a) indexes it: its layout does not depend on the eta count).
  const std::vector<double>& ln_total_eta() const { return total_eta.empty() ? eta : total_eta; }

  double radius(std::size_t k) const { return std::exp(ln_r0 + d_ln_r * static_cast<double>(k)); }
  std::size_t node(std::size_t e, std::size_t gi, std::size_t a) const {
    return (e * g.size() + gi) * albedo_prime.size() + a;
  }
  std::size_t index(std::size_t e, std::size_t gi, std::size_t a, std::size_t k) const {
    return node(e, gi, a) * radii + k;
  }
  std::size_t nodes() const { return eta.size() * g.size() * albedo_prime.size(); }
  // Throws InvalidInput naming what is inconsistent (sizes, order, values).
  void validate() const;
};

// Binary file (version 3): magic "BSSRDFX1", a little-endian uint64 header length, a JSON header
// (axes, layout, provenance), then ln_y (float32), total (float64) and, with a total_eta axis,
// fine_total (float64), little-endian. The relative errors live beside it in PATH.errors (magic
// "BSSRDFE1", a uint64 count, the uint16 values in ln_y's order): the model never reads them, and
// without them the table with version 7's nodes stays under 2 MiB. Versions 1 and 2 (errors inline
// after ln_y; version 1 without fine totals) still load. Throws InvalidInput (field "exact table")
// on a malformed or truncated file.
enum class TableErrors { skip, read };  // read: relative_error filled (from PATH.errors in version 3)
ExactTable read_exact_table(const std::string& path, TableErrors errors = TableErrors::skip);
// Writes PATH (version 3) and, when the table holds relative errors, PATH.errors.
void write_exact_table(const ExactTable& table, const std::string& path);

// The table shipped with the project, loaded on first use (thread-safe). Looked up in
// $BSSRDF_EXACT_TABLE, next to the executable (../share/bssrdf/exact/), the install prefix and the
// source tree. Throws InvalidInput naming the places searched when none has it.
const ExactTable& bundled_exact_table();
std::string bundled_exact_table_path();  // where it was found ("" before the first load)

}  // namespace bssrdf
