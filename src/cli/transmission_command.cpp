// bssrdf transmission: total transmittance (and reflectance) of a slab of the material against
// its thickness: what real-time engines need for thin-object translucency. Adding-doubling
// (exact at every thickness) by default; with --model multipole, thicknesses where the multipole
// is invalid (below 2 transport mean free paths, or negative transmittance) print no number:
// "invalid" in the table, null in JSON, empty in CSV.
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bssrdf/adding_doubling/slab.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/layers.hpp"
#include "bssrdf/lut/transmission_table.hpp"
#include "bssrdf/models/multipole.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace bssrdf::cli {

Action register_transmission(CLI::App& app) {
  struct Options {
    MediumOptions medium;
    OutputOptions output;
    std::string thickness, d_min, d_max, model = "adding-doubling";
    int samples = 0;  // 0: kThicknessSamples
  };
  auto options = std::make_shared<Options>();
  auto* sub =
      app.add_subcommand("transmission",
                         "Total transmittance and reflectance of a slab against its thickness (adding-doubling or "
                         "multipole, per unit entered flux, diffuse light only: the ballistic part is excluded)");
  options->medium.add_to(*sub);
  auto* list = sub->add_option("--thickness", options->thickness, "Thicknesses in --unit, comma-separated");
  sub->add_option("--model", options->model, "adding-doubling (exact) or multipole (for comparison) [adding-doubling]")
      ->check(CLI::IsMember({"adding-doubling", "multipole"}));
  // The default range is the library's rule (default_thickness_range), shared with lut --kind transmission.
  auto* lo = sub->add_option(
      "--d-min", options->d_min,
      "Smallest thickness [0.1 of the shortest transport mfp over the channels; multipole: 2 of the longest]");
  auto* hi = sub->add_option("--d-max", options->d_max,
                             "Largest thickness [40 of the longest transport mfp over the channels]");
  auto* n = add_count_option(*sub, "--samples", options->samples, 2, kMaxThicknessSamples,
                             "Number of thicknesses, log-spaced [" + std::to_string(kThicknessSamples) + "]");
  list->excludes(lo)->excludes(hi)->excludes(n);
  options->output.add_to(*sub);
  return [options] {
    const auto resolved = options->medium.resolve();
    const auto& medium = resolved.medium;
    const double mm = millimetres_per(resolved.unit);
    const bool ad = options->model == "adding-doubling";
    TransmissionTableOptions rule;
    rule.model = options->model;
    const auto thickness = slab_thicknesses(options->thickness, options->d_min, options->d_max, options->samples,
                                            resolved.unit, default_thickness_range(medium, rule));  // in unit
    struct Cell {
      double R, T;
      std::string invalid;  // the first invalid code, empty when valid
    };
    std::vector<std::vector<Cell>> rows;
    for (double d : thickness) {
      const multipole::Model model(d * mm);
      std::vector<Cell> row;
      if (ad) {  // per entered flux, ballistic beam removed from T, as the multipole reports it
        const auto stack = LayerStack::slab(medium, d * mm);
        for (std::size_t c = 0; c < medium.channels(); ++c) {
          const auto t =
              adding_doubling::solve(adding_doubling::slab_of(stack, c), adding_doubling::Incidence::collimated);
          row.push_back({t.diffuse_reflectance * t.entered_scale(),
                         (t.total_transmittance - t.unscattered_transmittance) * t.entered_scale(), ""});
        }
        rows.push_back(row);
        continue;
      }
      for (std::size_t c = 0; c < medium.channels(); ++c) {
        const auto m = medium.reduced(c);
        Cell cell{model.total_reflectance(m), model.total_transmittance(m), ""};
        for (const auto& note : model.validity(m))
          if (note.severity == Severity::invalid && cell.invalid.empty() &&
              (note.code == "thin_slab" || note.code == "source_outside_slab" || note.code.rfind("negative_", 0) == 0))
            cell.invalid = note.code;
        row.push_back(cell);
      }
      rows.push_back(row);
    }
    const std::string u(symbol(resolved.unit));
    std::ostringstream table, csv;
    table << (ad ? "adding-doubling slab (exact)" : "multipole slab (Donner & Jensen 2005)") << ", eta "
          << format_number(medium.eta) << ", per unit entered flux, diffuse light only (no ballistic part)\n"
          << "thickness (" << u << ")";
    csv << "thickness_" << u;
    for (const auto& name : medium.channel_names) {
      table << "   T_total " << name << "   R_total " << name;
      csv << ",T_total_" << name << ",R_total_" << name;
    }
    table << '\n';
    csv << '\n';
    nlohmann::json doc;
    doc["tool"] = std::string("bssrdf ") + BSSRDF_VERSION;
    doc["model"] = options->model;
    doc["normalization"] = "per_entered_flux";
    doc["ballistic_included"] = false;
    doc["unit"] = u;
    doc["eta"] = medium.eta;
    doc["channels"] = medium.channel_names;
    doc["rows"] = nlohmann::json::array();
    for (std::size_t i = 0; i < rows.size(); ++i) {
      char buffer[64];
      std::snprintf(buffer, sizeof buffer, "%14.5g", thickness[i]);
      table << buffer;
      csv << format_number(thickness[i]);
      nlohmann::json row{{"thickness", thickness[i]}};
      for (std::size_t c = 0; c < rows[i].size(); ++c) {
        const auto& cell = rows[i][c];
        if (cell.invalid.empty()) {
          std::snprintf(buffer, sizeof buffer, "%12.5f%12.5f", cell.T, cell.R);
          table << buffer;
          csv << ',' << format_number(cell.T) << ',' << format_number(cell.R);
          row["total_transmittance"].push_back(cell.T);
          row["total_reflectance"].push_back(cell.R);
        } else {
          std::snprintf(buffer, sizeof buffer, "%12s%12s", "invalid", "invalid");
          table << buffer;
          csv << ",,";
          row["total_transmittance"].push_back(nullptr);
          row["total_reflectance"].push_back(nullptr);
        }
        row["invalid"].push_back(cell.invalid.empty() ? nlohmann::json(nullptr) : nlohmann::json(cell.invalid));
      }
      table << '\n';
      csv << '\n';
      doc["rows"].push_back(row);
    }
    if (!ad)
      table << "invalid: the multipole does not hold (thinner than 2 transport mean free paths, or negative "
               "transmittance); use 'bssrdf reference --thickness D' (Monte Carlo) there\n";
    emit(
        options->output, [&] { return doc.dump(2) + "\n"; }, [&] { return csv.str(); }, table.str());
  };
}

}  // namespace bssrdf::cli
