// The table kinds of `bssrdf lut`: each one parses its options into the library's option types
// (whose defaults are the command's), builds its table and returns it with the library's summary.
// Adding a kind is one builder in lut_kinds.cpp and one row of table_kinds().
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <span>
#include <string>
#include <string_view>

#include "bssrdf/lut/lookup_table.hpp"
#include "cli_common.hpp"

namespace bssrdf::cli {

// What the command line gave; empty strings and zero counts mean "the library's default".
struct LutOptions {
  MediumOptions medium;
  std::string kind = "radial", model = "pbd", accuracy, tolerance, energy, interpolation;
  std::string output, format, output_dir, layout = "pbrt", size, table_tolerance;
  bool half = false, all = false, quiet = false;
  unsigned threads = 1;
  bool model_given = false;    // --model appeared on the command line
  bool photons_given = false;  // --photons appeared on the command line
  // transmission
  std::string thickness, d_min, d_max;
  int samples = 0;  // 0: kThicknessSamples
  bool reference = false, reference_everywhere = false;
  std::string layers;  // radial --reference: a layer stack file instead of a medium
  std::uint64_t photons = 0, seed = 1;
  // preintegrated, penumbra
  std::string curvature_max, width_max;
  // separable
  int taps = 0;  // 0: the library's
  std::string range, band;
  // gaussians
  int count = 0;  // 0: quantized diffusion's own mixture with --model quantized, else 6
  std::string preview;  // PNG file
  // --pixel: how wrong the table looks at that pixel size (with --tolerance: sized by it)
  std::string pixel;
  bool taps_given = false, range_given = false, size_given = false, count_given = false;
};

// A table and the lines for people about it.
struct Built {
  LookupTable table;
  std::string summary;
  std::map<std::string, std::function<std::string()>> other_formats;  // e.g. "glsl", "hlsl" for kernels, on demand
};

struct TableKind {
  std::string_view name;
  Built (*build)(const LutOptions&);
  std::string_view summary;  // one line for --help
};
std::span<const TableKind> table_kinds();
// The kind named o.kind; throws InvalidInput naming --kind with the accepted names.
const TableKind& table_kind(const std::string& name);

// The PNG preview (any kind; the model is --model where given, else pbd) and a line about it.
struct RenderedPreview {
  std::string png, description;
};
RenderedPreview render_preview(const LutOptions& o, const MediumOptions::Resolved& resolved);

}  // namespace bssrdf::cli
