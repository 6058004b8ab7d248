#include "bssrdf/io/renderer_export.hpp"

#include <cctype>
#include <cmath>

#include "export_common.hpp"

namespace bssrdf {
namespace {
const std::pair<RendererTarget, const char*> kTargets[] = {{RendererTarget::json, "json"},
                                                           {RendererTarget::pbrt_v4, "pbrt-v4"},
                                                           {RendererTarget::mitsuba3, "mitsuba3"},
                                                           {RendererTarget::blender, "blender"},
                                                           {RendererTarget::unity_hdrp, "unity-hdrp"},
                                                           {RendererTarget::unity_hdrp_editor, "unity-hdrp-editor"},
                                                           {RendererTarget::unreal, "unreal"},
                                                           {RendererTarget::unreal_python, "unreal-python"}};
}  // namespace

std::vector<std::string> renderer_target_names() {
  std::vector<std::string> out;
  for (const auto& [t, name] : kTargets) out.push_back(name);
  return out;
}

RendererTarget parse_renderer_target(std::string_view text) {
  std::string names;
  for (const auto& [t, name] : kTargets) {
    if (text == name) return t;
    names += (names.empty() ? "" : ", ") + std::string(name);
  }
  throw InvalidInput("to", "'" + std::string(text) + "'", "one of " + names);
}

std::string_view to_string(RendererTarget target) {
  for (const auto& [t, name] : kTargets)
    if (t == target) return name;
  return "?";
}

SingleG single_g(const Medium& medium) {
  SingleG out;
  double sum = 0;
  int count = 0;
  for (std::size_t c = 0; c < medium.channels(); ++c)
    if (medium.sigma_s[c] > 0) sum += medium.g[c], ++count;
  out.g = count ? sum / count : 0;
  for (std::size_t c = 0; c < medium.channels(); ++c) {
    if (medium.sigma_s[c] > 0 && medium.g[c] != out.g) out.exact = false;
    out.sigma_s.push_back(medium.g[c] == out.g ? medium.sigma_s[c]
                                               : medium.sigma_s[c] * (1 - medium.g[c]) / (1 - out.g));
  }
  return out;
}

double burley_searchlight_scaling(double A) { return 1.85 - A + 7 * std::pow(std::abs(A - 0.8), 3); }

std::string export_materials(RendererTarget target, const std::vector<ExportEntry>& entries, LengthUnit unit,
                             const ExportOptions& options) {
  using namespace export_detail;
  if (entries.empty()) throw InvalidInput("export: no materials given");
  for (const auto& e : entries) {
    if (e.material.medium.channel_names != entries.front().material.medium.channel_names ||
        e.material.medium.wavelength_nm != entries.front().material.medium.wavelength_nm)
      throw InvalidInput("export: material " + e.material.name + " has other channels than " +
                         entries.front().material.name + "; export them separately");
    if (target != RendererTarget::json && e.derived.channels.size() != e.material.medium.channels())
      throw InvalidInput("export: derived quantities missing for " + e.material.name);
  }
  switch (target) {
    case RendererTarget::json:
      return export_json(entries, unit);
    case RendererTarget::pbrt_v4:
      return export_pbrt_v4(entries, unit);
    case RendererTarget::mitsuba3:
      return export_mitsuba3(entries, unit);
    case RendererTarget::blender:
      return export_blender(entries, unit, options);
    case RendererTarget::unity_hdrp:
      return export_unity_hdrp(entries, unit);
    case RendererTarget::unity_hdrp_editor:
      return export_unity_hdrp_editor(entries, unit);
    case RendererTarget::unreal:
      return export_unreal(entries);
    case RendererTarget::unreal_python:
      return export_unreal_python(entries);
  }
  return "";
}

namespace export_detail {

std::string identifier(const std::string& name) {
  std::string out;
  for (unsigned char c : name) out += std::isalnum(c) ? static_cast<char>(std::tolower(c)) : '_';
  if (out.empty() || std::isdigit(static_cast<unsigned char>(out[0]))) out = "m_" + out;
  return out;
}

std::string validity_summary(const DerivedQuantities& derived) {
  std::string valid, problems;
  for (const auto& c : derived.channels) {
    bool any = false;
    for (const auto& note : c.validity)
      if (note.severity != Severity::note) {
        problems += (problems.empty() ? "" : "; ") + c.name + ": " + describe(note);
        any = any || note.severity == Severity::invalid;
      }
    if (!any) valid += (valid.empty() ? "" : ", ") + c.name;
  }
  const std::string model =
      (derived.colour.empty() ? "" : derived.colour + "; ") + "the " + derived.physical_model + " profile";
  if (problems.empty()) return model + " valid in every channel (object size " + num(derived.object_size_mm) + " mm)";
  return model + " valid in " + (valid.empty() ? std::string("no channel") : valid) + "; " + problems;
}

}  // namespace export_detail
}  // namespace bssrdf
