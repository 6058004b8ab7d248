// Shared by the renderer exporters (one file per target): number formatting, the header every
// export opens with, and the checks all targets share.
#pragma once

#include <string>
#include <vector>

#include "bssrdf/error.hpp"
#include "bssrdf/io/renderer_export.hpp"

namespace bssrdf::export_detail {

// Shortest round-trip form, so exported numbers reload bit-exactly.
inline std::string num(double v) { return format_number(v); }

inline std::string join(const std::vector<double>& values, const std::string& separator) {
  std::string out;
  for (std::size_t i = 0; i < values.size(); ++i) out += (i ? separator : "") + num(values[i]);
  return out;
}

// RGB targets need three channels.
inline void require_rgb(const std::vector<ExportEntry>& entries, std::string_view target) {
  for (const auto& e : entries)
    if (e.material.medium.channels() != 3)
      throw InvalidInput("material " + e.material.name + ": " + std::to_string(e.material.medium.channels()) +
                         " channels; " + std::string(target) + " takes exactly three (RGB)");
}

// Letters, digits and '_' only: for identifiers (XML ids, Python names).
std::string identifier(const std::string& name);

// "diffusion valid in R, G; not in B: <reason>"
std::string validity_summary(const DerivedQuantities& derived);

std::string export_json(const std::vector<ExportEntry>& entries, LengthUnit unit);
std::string export_pbrt_v4(const std::vector<ExportEntry>& entries, LengthUnit unit);
std::string export_mitsuba3(const std::vector<ExportEntry>& entries, LengthUnit unit);
std::string export_blender(const std::vector<ExportEntry>& entries, LengthUnit unit, const ExportOptions& options);
std::string export_unity_hdrp(const std::vector<ExportEntry>& entries, LengthUnit unit);
std::string export_unreal(const std::vector<ExportEntry>& entries);
std::string export_unity_hdrp_editor(const std::vector<ExportEntry>& entries, LengthUnit unit);
std::string export_unreal_python(const std::vector<ExportEntry>& entries);

}  // namespace bssrdf::export_detail
