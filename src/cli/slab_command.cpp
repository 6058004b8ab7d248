// bssrdf slab: exact totals of a slab (or layer stack) by adding-doubling: diffuse and specular
// reflectance, total and unscattered transmittance per channel, per incident flux (as MCML and
// Prahl's ad report them) and per entered flux.
#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "bssrdf/adding_doubling/slab.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/io/layers_json.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace bssrdf::cli {

namespace {

struct SlideOption {
  double n, thickness_mm;
};

// "--slides N,D": index and thickness (in `unit`) of one glass slide on each side.
SlideOption parse_slides(const std::string& text, LengthUnit unit) {
  const auto v = parse_number_list(text, "--slides");
  if (v.size() != 2) throw InvalidInput("--slides", text, "two numbers: index,thickness (e.g. 1.5,1)");
  if (!(v[0] >= 1 && v[0] <= 4)) throw InvalidInput("--slides index", format_number(v[0]), "1 to 4");
  if (!(v[1] > 0 && std::isfinite(v[1])))
    throw InvalidInput("--slides thickness", format_number(v[1]), "> 0 and finite");
  return {v[0], to_mm(v[1], unit)};
}

nlohmann::json totals_json(const adding_doubling::Totals& t, double scale, const char* normalization) {
  return {{"normalization", normalization},
          {"diffuse_reflectance", t.diffuse_reflectance * scale},
          {"total_transmittance", t.total_transmittance * scale},
          {"unscattered_transmittance", t.unscattered_transmittance * scale},
          {"absorbed", t.absorbed() * scale}};
}

}  // namespace

Action register_slab(CLI::App& app) {
  struct Options {
    MediumOptions medium;
    OutputOptions output;
    std::string thickness, layers, slides, incidence = "collimated";
    double tolerance = adding_doubling::Options{}.tolerance;
    int points = 0;
  };
  auto options = std::make_shared<Options>();
  auto* sub =
      app.add_subcommand("slab",
                         "Exact totals of a slab or layer stack by adding-doubling: diffuse and specular reflectance, "
                         "total and unscattered transmittance (glass slides, collimated or diffuse light)");
  options->medium.add_to(*sub);
  auto* thickness = sub->add_option("--thickness", options->thickness, "Slab thickness in --unit [semi-infinite]");
  auto* layers = sub->add_option("--layers", options->layers, "Layer stack file (JSON, format bssrdf-layers)");
  sub->add_option("--slides", options->slides, "Glass slides on both faces: index,thickness (in --unit), e.g. 1.5,1");
  sub->add_option("--incidence", options->incidence, "collimated (normal beam) or diffuse [collimated]")
      ->check(CLI::IsMember({"collimated", "diffuse"}));
  sub->add_option("--tolerance", options->tolerance, "Accuracy goal of R and T; sets the number of angles [1e-4]");
  sub->add_option("--points", options->points,
                  "Fixed number of quadrature angles per hemisphere (overrides --tolerance)");
  options->output.add_to(*sub);
  layers->excludes(thickness);
  auto* unit_option = sub->get_option("--unit");

  return [options, unit_option] {
    const auto& o = *options;
    LayerStack stack;
    LengthUnit unit = LengthUnit::millimetre;
    std::string source;
    if (!o.layers.empty()) {
      if (!o.medium.material.empty() || !o.medium.sigma_a.empty() || !o.medium.sigma_s.empty() || !o.medium.g.empty() ||
          !o.medium.eta.empty())
        throw InvalidInput(
            "--layers describes the medium: do not combine it with --material, --sigma-a, --sigma-s, --g or --eta");
      const auto file = read_layers_json(o.layers);
      stack = file.stack;
      unit = unit_option->count() ? parse_length_unit(o.medium.unit, "--unit") : file.unit;
      source = o.layers;
    } else {
      const auto resolved = o.medium.resolve();
      unit = resolved.unit;
      double d = kSemiInfinite;
      if (!o.thickness.empty()) {
        d = parse_number(o.thickness, "--thickness");
        if (!(d > 0 && std::isfinite(d)))
          throw InvalidInput("--thickness", o.thickness, "> 0 and finite (omit for semi-infinite)");
        d = to_mm(d, unit);
      }
      stack = LayerStack::slab(resolved.medium, d);
      source = resolved.material ? resolved.material->name : "medium";
    }
    if (!(o.tolerance >= 1e-8 && o.tolerance <= 0.1))
      throw InvalidInput("--tolerance", format_number(o.tolerance), "1e-8 to 0.1");
    if (o.points != 0 && !(o.points >= 4 && o.points <= 256))
      throw InvalidInput("--points", std::to_string(o.points), "4 to 256");
    const auto incidence = adding_doubling::parse_incidence(o.incidence);
    std::optional<SlideOption> slide;
    if (!o.slides.empty()) {
      slide = parse_slides(o.slides, unit);
      if (stack.semi_infinite()) throw InvalidInput("--slides", o.slides, "a finite slab (give --thickness)");
      Layer glass;
      glass.name = "slide";
      glass.n = slide->n;
      glass.thickness = slide->thickness_mm;
      glass.sigma_a.assign(stack.channels(), 0);
      glass.sigma_s.assign(stack.channels(), 0);
      glass.g.assign(stack.channels(), 0);
      stack.layers.insert(stack.layers.begin(), glass);
      stack.layers.push_back(glass);
    }
    stack.validate();
    adding_doubling::Options ad;
    ad.tolerance = o.tolerance;
    ad.points = o.points;
    std::vector<adding_doubling::Totals> totals;
    for (std::size_t c = 0; c < stack.channels(); ++c)
      totals.push_back(adding_doubling::solve(adding_doubling::slab_of(stack, c), incidence, ad));

    const std::string u(symbol(unit));
    const double mm = millimetres_per(unit);
    nlohmann::json doc;
    doc["tool"] = std::string("bssrdf ") + BSSRDF_VERSION;
    doc["solver"] = "adding-doubling";
    doc["source"] = source;
    doc["incidence"] = std::string(adding_doubling::to_string(incidence));
    doc["unit"] = u;
    doc["normalization"] = "per_incident_flux";
    doc["ambient_above"] = stack.ambient_above;
    doc["ambient_below"] = stack.ambient_below;
    if (stack.semi_infinite() && stack.layers.size() == 1)
      doc["thickness"] = nullptr;
    else if (o.layers.empty())
      doc["thickness"] = stack.layers[slide ? 1 : 0].thickness / mm;
    doc["slides"] =
        slide ? nlohmann::json{{"n", slide->n}, {"thickness", slide->thickness_mm / mm}} : nlohmann::json(nullptr);
    doc["channels"] = nlohmann::json::array();
    std::ostringstream table, csv;
    table << "adding-doubling, " << adding_doubling::to_string(incidence) << " incidence, " << source;
    if (!o.layers.empty())
      table << " (" << stack.layers.size() << " layers)";
    else
      table << ", "
            << (stack.semi_infinite() ? std::string("semi-infinite")
                                      : format_number(doc["thickness"].get<double>()) + " " + u);
    if (slide)
      table << ", slides n " << format_number(slide->n) << " x " << format_number(slide->thickness_mm / mm) << " " << u;
    table << "\nper unit incident flux (per entered flux in brackets)\n"
          << "channel      R_diffuse            R_specular   T_total              T_unscattered  angles  error\n";
    csv << "channel,normalization,diffuse_reflectance,specular_reflectance,total_transmittance,unscattered_"
           "transmittance,absorbed,"
           "quadrature_points,error_estimate\n";
    for (std::size_t c = 0; c < totals.size(); ++c) {
      const auto& t = totals[c];
      const auto& name = stack.channel_names[c];
      auto ch = totals_json(t, 1, "per_incident_flux");
      ch["name"] = name;
      ch["specular_reflectance"] = t.specular_reflectance;
      ch["quadrature_points"] = t.points;
      ch["error_estimate"] = t.error_estimate;
      ch["per_entered_flux"] = totals_json(t, t.entered_scale(), "per_entered_flux");
      doc["channels"].push_back(ch);
      char line[256];
      std::snprintf(line, sizeof line, "%-12s %.5f (%.5f)    %.5f      %.5f (%.5f)    %.5f        %4d  %.1e\n",
                    name.c_str(), t.diffuse_reflectance, t.diffuse_reflectance * t.entered_scale(),
                    t.specular_reflectance, t.total_transmittance, t.total_transmittance * t.entered_scale(),
                    t.unscattered_transmittance, t.points, t.error_estimate);
      table << line;
      for (double scale : {1.0, t.entered_scale()})
        csv << name << ',' << (scale == 1.0 ? "per_incident_flux" : "per_entered_flux") << ','
            << format_number(t.diffuse_reflectance * scale) << ',' << format_number(t.specular_reflectance) << ','
            << format_number(t.total_transmittance * scale) << ',' << format_number(t.unscattered_transmittance * scale)
            << ',' << format_number(t.absorbed() * scale) << ',' << t.points << ',' << format_number(t.error_estimate)
            << '\n';
    }
    table << "R_diffuse excludes the specular reflection; T_total includes the unscattered beam\n";
    emit(
        o.output, [&] { return doc.dump(2) + "\n"; }, [&] { return csv.str(); }, table.str());
  };
}

}  // namespace bssrdf::cli
