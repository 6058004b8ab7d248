// The table kinds of `bssrdf lut`: each one parses its flags into the library's options
// (lut/table_kinds.hpp, whose defaults are the command's) and calls the library's entry point for it.
// Adding a kind is one entry point in the library, one parser in lut_kinds.cpp and one row of table_kinds().
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>

#include "bssrdf/lut/table_kinds.hpp"
#include "cli_common.hpp"
#include "colour_options.hpp"

namespace bssrdf::cli {

// What the command line gave; empty strings and zero counts mean "the library's default".
struct LutOptions {
  MediumOptions medium;
  ColourOptions colour;  // a spectral medium's profile kinds as R, G, B integrated per radius
  std::string kind = "radial", model, accuracy, tolerance, energy, interpolation;
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
  int count = 0;        // 0: quantized diffusion's own mixture with --model quantized, else 6
  std::string preview;  // PNG file
  // --pixel: how wrong the table looks at that pixel size (with --tolerance: sized by it)
  std::string pixel;
  bool taps_given = false, range_given = false, size_given = false, count_given = false;
};

struct TableKind {
  std::string_view name;
  BuiltTable (*build)(const LutOptions&);
  std::string_view summary;  // one line for --help
};
std::span<const TableKind> table_kinds();
// The kind named o.kind; throws InvalidInput naming --kind with the accepted names.
const TableKind& table_kind(const std::string& name);

// Option parsing shared by the kinds (lut_options.cpp).
// "WxH" with each side a count in its range (parsed as signed: "-1x10" is refused, not wrapped).
std::pair<std::size_t, std::size_t> parse_grid(const std::string& text, std::int64_t min_w, std::int64_t max_w,
                                               std::int64_t min_h, std::int64_t max_h, const std::string& example);
// --size WxH for the realtime grids; empty keeps the library's size.
void parse_size(const std::string& text, std::size_t& width, std::size_t& height);
double positive_fraction(const std::string& text, const std::string& field);  // 0 < value < 1
// A length option in --unit, > 0, as mm.
double positive_length_mm(const std::string& text, const std::string& field, LengthUnit unit);
// --pixel [--tolerance] for the kinds sized by an image error; nullopt without --pixel.
std::optional<ImageErrorCheck> image_check(const LutOptions& o, LengthUnit unit);

// The PNG preview (any kind; the model is --model where given, else pbd) and a line about it.
struct RenderedPreview {
  std::string png, description;
  std::string warning;  // one line for stderr when colours were clipped for display; empty otherwise
};
RenderedPreview render_preview(const LutOptions& o, const MediumOptions::Resolved& resolved);

}  // namespace bssrdf::cli
