#include "bssrdf/lut/table_context.hpp"

#include "bssrdf/error.hpp"

namespace bssrdf {
namespace {

std::string join(const std::vector<double>& values, double scale) {
  std::string out;
  for (double v : values) {
    if (!out.empty()) out += ',';
    out += format_number(v * scale);
  }
  return out;
}

}  // namespace

void describe(LookupTable& table, const TableContext& context) {
  table.set("bssrdf:tool", std::string("bssrdf ") + BSSRDF_VERSION);
  table.set("bssrdf:kind", table.kind);
  if (context.material) {
    table.set("bssrdf:material", context.material->name);
    table.set("bssrdf:material_source", context.material->source);
    table.set("bssrdf:material_citation", context.material->citation);
  } else {
    table.set("bssrdf:material", std::string("(coefficients given)"));
  }
  if (context.model) {
    table.set("bssrdf:model", context.model->name());
    table.set("bssrdf:model_description", context.model->description());
    if (!context.model_choice.empty()) table.set("bssrdf:model_choice", context.model_choice);
    table.set("bssrdf:includes_single_scattering",
              std::string(context.model->includes_single_scattering() ? "yes" : "no"));
  }
  if (context.medium) {
    const double mm = millimetres_per(context.unit);
    // A colour table of a spectral medium's own coefficients (transmission) has the colour's channels; its
    // coefficients are per wavelength of bssrdf:colour_wavelength_nm.
    const bool per_wavelength = context.colour && context.medium->spectral();
    std::string names;
    for (const auto& n : context.medium->channel_names) names += (names.empty() ? "" : ",") + n;
    table.set("bssrdf:channels", per_wavelength ? std::string("R,G,B") : names);
    table.set("bssrdf:eta", context.medium->eta);
    const std::string per_unit = "1/" + std::string(symbol(context.unit));
    table.set("bssrdf:sigma_a", join(context.medium->sigma_a, mm) + " " + per_unit);
    table.set("bssrdf:sigma_s", join(context.medium->sigma_s, mm) + " " + per_unit);
    table.set("bssrdf:g", join(context.medium->g, 1.0));
    // A spectral medium: its channels' wavelengths (the OpenEXR writer lays them out as spectral channels).
    if (context.medium->spectral() && !per_wavelength)
      table.set("bssrdf:wavelength_nm", join(context.medium->wavelength_nm, 1.0));
  }
  if (context.colour) {  // the R, G, B channels integrated from the spectral medium's wavelengths
    const auto& note = context.colour->note;
    table.set("bssrdf:colour", context.colour->line);
    table.set("bssrdf:colour_observer", note.observer);
    table.set("bssrdf:colour_illuminant", note.illuminant);
    table.set("bssrdf:colour_space", note.space);
    table.set("bssrdf:colour_wavelength_nm", join(note.wavelength_nm, 1.0));
  }
}

LookupTable described_table(std::string kind, std::size_t width, std::size_t height, const TableContext& context) {
  LookupTable out;
  out.kind = std::move(kind);
  out.width = width;
  out.height = height;
  describe(out, context);
  out.set("bssrdf:unit", std::string(symbol(context.unit)));
  return out;
}

}  // namespace bssrdf
