// The files for an advised representation (`bssrdf advise --write DIR`), as bssrdf-lut JSON, the
// format `bssrdf lut` writes, named DIR/STEM.REPRESENTATION.json (':' becomes '_'):
//  - lambertian: kind "albedo", one value per channel (the reference's diffuse reflectance);
//  - radial-table-N:MODEL: kind "radial-log", the N radii and R(r) per channel (each channel its
//    own radii, radial_table_nodes()), linear in (ln r, ln R), 0 beyond;
//  - gaussians-K:MODEL: the `lut --kind gaussians` table of K Gaussians fitted to MODEL;
//  - separable-N:MODEL: the `lut --kind separable` kernel of N taps over the advised range;
//  - preintegrated-N:MODEL: the `lut --kind preintegrated` table, N x N, the advised curvature range;
//  - reference-table: against a Monte Carlo reference the `lut --kind radial --reference` table (same
//    photons and seed as advised); against a reference with formula channels (exact, auto) a
//    "radial-log" table of the nodes it was judged on (Advice::reference_table);
//  - an analytic model: the `lut --kind radial --model MODEL` table.
// Each records the advice (bssrdf:advice) and its image error and pixel size (bssrdf:image_error,
// bssrdf:image_error_pixel_mm).
#pragma once

#include <filesystem>
#include <optional>

#include "bssrdf/advise/advise.hpp"
#include "bssrdf/materials.hpp"

namespace bssrdf {

// Writes the chosen candidate's file (atomically; creates DIR). Returns its path. Throws
// InvalidInput when the advice has no choice or DIR cannot be created.
std::filesystem::path write_advised_file(const std::filesystem::path& dir, const std::string& stem,
                                         const Medium& medium, const std::optional<Material>& material,
                                         const Advice& advice, const MonteCarloReferenceOptions& reference);

}  // namespace bssrdf
