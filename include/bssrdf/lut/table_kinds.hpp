// The table kinds `bssrdf lut` writes, each from its options to a LookupTable ready to encode and the
// lines for people about it: the kind's own summary (beside its to_lookup_table), and where asked how
// it was sized and how wrong it looks at a pixel size (image/realtime_tables.hpp). One entry point a
// kind; a caller (the command line, a script, a renderer's build step) only fills the options.
//
//   const auto pbd = make_model("pbd");
//   const TableContext skin{material, &medium, pbd.get(), LengthUnit::millimetre};
//   BuiltTable radial = tabulate_radial(skin, {});
//   write_file_atomically("skin1.exr", encode_exr(radial.table));
//   std::cout << radial.summary;
//
// Each kind's options hold the library's defaults; a context gives the medium (1/mm), the model a
// profile kind tabulates, the material it came from and the unit the table is written in.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bssrdf/layers.hpp"
#include "bssrdf/lut/albedo_radius_table.hpp"
#include "bssrdf/lut/lookup_table.hpp"
#include "bssrdf/lut/penumbra_table.hpp"
#include "bssrdf/lut/preintegrated_table.hpp"
#include "bssrdf/lut/radial_table.hpp"
#include "bssrdf/lut/reference_radial_table.hpp"
#include "bssrdf/lut/separable_kernel.hpp"
#include "bssrdf/lut/table_context.hpp"
#include "bssrdf/lut/transmission_table.hpp"
#include "bssrdf/spectral/colour.hpp"

namespace bssrdf {

// A table and what people are told about it.
struct BuiltTable {
  LookupTable table;
  std::string summary;  // lines, each ending in '\n'
  // Encodings besides EXR, JSON and CSV, made on demand: "glsl" and "hlsl" for a separable kernel.
  // One that cannot be made (a kernel without three channels) throws InvalidInput naming "format".
  std::map<std::string, std::function<std::string()>> other_formats;
};

// How wrong a table looks in an image, against the model it tabulates (bssrdf:image_error, 8-bit
// sRGB code values at a shadow edge, a light line and a flat region); with a tolerance, the kind's
// size is the smallest that meets it (the most accurate tried when none does, and the summary says so).
struct ImageErrorCheck {
  double pixel = 0;                 // mm, > 0
  std::optional<double> tolerance;  // code values, > 0
};

// R(r) of context.model with its sampling CDF and inverse; with an image tolerance, the relative
// interpolation tolerance is chosen by it (table.tolerance is then ignored).
struct RadialKindOptions {
  RadialTableOptions table;
  std::optional<ImageErrorCheck> image;
};
BuiltTable tabulate_radial(const TableContext& context, const RadialKindOptions& options);

// The Monte Carlo reference's R(r) with standard errors: for the half-space of context.medium, or
// for a layer stack (context: the unit only), recorded as bssrdf:layers "source (N layers)".
BuiltTable tabulate_reference_radial(const TableContext& context, const ReferenceRadialOptions& options);
BuiltTable tabulate_reference_radial(const LayerStack& stack, const std::string& source, const TableContext& context,
                                     const ReferenceRadialOptions& options);

// pbrt's dimensionless photon-beam-diffusion table for one (g, eta); recorded with the material they
// came from, if any, and the layout's name (bssrdf:layout).
enum class AlbedoRadiusLayoutRule { pbrt, family, adaptive };
struct AlbedoRadiusKindOptions {
  double g = 0, eta = 1.3;
  std::optional<Material> material;
  AlbedoRadiusLayoutRule layout = AlbedoRadiusLayoutRule::pbrt;
  std::size_t albedos = 64, radii = 48;              // family
  double table_tolerance = kAdaptiveTableTolerance;  // adaptive: the interpolation error allowed
  AlbedoRadiusOptions table;                         // table.progress: the adaptive layout's search
};
BuiltTable tabulate_albedo_radius(const AlbedoRadiusKindOptions& options);
std::string to_string(AlbedoRadiusLayoutRule layout);  // "pbrt", "family", "adaptive"

// Total transmittance of slabs of context.medium at thickness_mm (mm), by options.model, with the
// model description that says which solver made which rows. With `colour` (a spectral medium), the table's channels
// are R, G, B: each wavelength's slab solved, then integrated per thickness (spectral/colour_transmission.hpp), and
// recorded as the context's colour.
BuiltTable tabulate_transmission(const TableContext& context, std::vector<double> thickness_mm,
                                 const TransmissionTableOptions& options,
                                 const std::optional<spectral::ColourSettings>& colour = std::nullopt);

// Pre-integrated skin over (N.L, curvature); with an image tolerance the size is chosen (unless
// size_given), and curvature_max with it (unless curvature_given).
struct PreintegratedKindOptions {
  PreintegratedOptions table;
  std::optional<ImageErrorCheck> image;
  bool size_given = false, curvature_given = false;
};
BuiltTable tabulate_preintegrated(const TableContext& context, const PreintegratedKindOptions& options);

BuiltTable tabulate_penumbra(const TableContext& context, const PenumbraOptions& options);

// A screen-space separable kernel, with GLSL and HLSL as other formats; with an image tolerance the
// taps and range are chosen (unless kernel_given: taps or range were given).
struct SeparableKindOptions {
  SeparableKernelOptions kernel;
  std::optional<ImageErrorCheck> image;
  bool kernel_given = false;
};
BuiltTable tabulate_separable(const TableContext& context, const SeparableKindOptions& options);

// A sum of Gaussians: `count` fitted (1 to 32); count 0: chosen by an image tolerance, else the
// model's own mixture where it has one (quantized diffusion), else 6 fitted.
struct GaussiansKindOptions {
  int count = 0;
  std::optional<ImageErrorCheck> image;
};
BuiltTable tabulate_gaussians(const TableContext& context, const GaussiansKindOptions& options);

}  // namespace bssrdf
