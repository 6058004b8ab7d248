// bssrdf materials list | show | export | import: the measured-media database, what each entry
// implies (derived quantities, diffusion validity), renderer exports, and fitted materials saved
// in the database's own format.
#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "../io/data_file.hpp"
#include "bssrdf/derived_quantities.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/fit/fit_import.hpp"
#include "bssrdf/io/atomic_file.hpp"
#include "bssrdf/io/renderer_export.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace bssrdf::cli {
namespace {

using json = nlohmann::ordered_json;

// A length in the output unit; infinite and NaN become null in JSON.
json length(double mm, LengthUnit unit) {
  const double v = from_mm(mm, unit);
  return std::isfinite(v) ? json(v) : json(nullptr);
}
json value(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }
json validity_json(const ValidityReport& report) {  // as `bssrdf profile -f json` writes it
  json out = json::array();
  for (const auto& note : report)
    out.push_back(
        {{"severity", std::string(to_string(note.severity))}, {"code", note.code}, {"message", note.message}});
  return out;
}

json show_json(const Material& m, const DerivedQuantities& q, LengthUnit unit) {
  const std::string u(symbol(unit)), per = "1/" + u;
  json doc = {
      {"name", m.name},
      {"source", m.source},
      {"citation", m.citation},
      {"file", m.file},
      {"eta", m.medium.eta},
      {"unit", u},
      {"reduced_scattering_only", m.reduced_scattering_only},
      {"physical_model", q.physical_model},
      {"object_size", from_mm(q.object_size_mm, unit)},
      {"conventions",
       {{"mfp", "1/sigma_t (unreduced), " + u},
        {"transport_mfp", "ell = 1/sigma_t', " + u},
        {"diffuse_mfp", "ell_d = 1/sigma_tr, sigma_tr = sqrt(3 sigma_a sigma_t'), " + u + "; null without absorption"},
        {"burley_d",
         "d of R(r) = A (e^{-r/d} + e^{-r/3d})/(8 pi d r), A = surface_albedo, least-squares fitted to the " +
             q.physical_model + " profile (each channel's physical_model), " + u +
             "; burley_fit_error = sqrt(int r (fit - R)^2 dr / int r R^2 dr)"},
        {"surface_albedo",
         "total diffuse reflectance per entered flux: the exact model's inside its domain; outside it the "
         "channel's physical model's, or where that exceeds 1 (the model creates energy) the exact total by "
         "adding-doubling, and the channel's validity says so (code surface_albedo)"},
        {"coefficients", per}}},
      {"notes", m.notes}};
  doc["channels"] = json::array();
  for (const auto& c : q.channels) {
    doc["channels"].push_back({{"name", c.name},
                               {"sigma_a", coefficient_from_per_mm(c.sigma_a, unit)},
                               {"sigma_s", coefficient_from_per_mm(c.sigma_s, unit)},
                               {"g", c.g},
                               {"sigma_t", coefficient_from_per_mm(c.sigma_t, unit)},
                               {"sigma_s_prime", coefficient_from_per_mm(c.sigma_s_prime, unit)},
                               {"sigma_t_prime", coefficient_from_per_mm(c.sigma_t_prime, unit)},
                               {"albedo", c.albedo},
                               {"albedo_prime", c.albedo_prime},
                               {"mfp", length(c.mfp, unit)},
                               {"transport_mfp", length(c.transport_mfp, unit)},
                               {"diffuse_mfp", length(c.diffuse_mfp, unit)},
                               {"burley_d", length(c.burley_d, unit)},
                               {"burley_albedo", value(c.burley_albedo)},
                               {"burley_fit_error", value(c.burley_error)},
                               {"physical_model", c.physical_model},
                               {"model_choice", c.model_choice},
                               {"surface_albedo", c.surface_albedo},
                               {"valid", c.valid()},
                               {"validity", validity_json(c.validity)}});
  }
  return doc;
}

std::string show_table(const Material& m, const DerivedQuantities& q, LengthUnit unit) {
  const std::string u(symbol(unit));
  std::ostringstream out;
  out << m.name << " (" << m.source << ")  eta " << m.medium.eta << "\n" << m.citation << "\n";
  for (const auto& n : m.notes) out << "  note: " << n << "\n";
  char line[256];
  std::snprintf(line, sizeof line, "%-24s", "");
  out << line;
  for (const auto& c : q.channels) {
    std::snprintf(line, sizeof line, "%14s", c.name.c_str());
    out << line;
  }
  out << "\n";
  auto row = [&](const std::string& label, auto get) {
    std::snprintf(line, sizeof line, "%-24s", label.c_str());
    out << line;
    for (const auto& c : q.channels) {
      std::snprintf(line, sizeof line, "%14.6g", get(c));
      out << line;
    }
    out << "\n";
  };
  const double mm = millimetres_per(unit);
  row("sigma_a [1/" + u + "]", [&](const DerivedChannel& c) { return c.sigma_a * mm; });
  row("sigma_s [1/" + u + "]", [&](const DerivedChannel& c) { return c.sigma_s * mm; });
  row("g", [](const DerivedChannel& c) { return c.g; });
  row("sigma_s' [1/" + u + "]", [&](const DerivedChannel& c) { return c.sigma_s_prime * mm; });
  row("albedo", [](const DerivedChannel& c) { return c.albedo; });
  row("albedo'", [](const DerivedChannel& c) { return c.albedo_prime; });
  row("mfp 1/sigma_t [" + u + "]", [&](const DerivedChannel& c) { return c.mfp / mm; });
  row("ell 1/sigma_t' [" + u + "]", [&](const DerivedChannel& c) { return c.transport_mfp / mm; });
  row("ell_d 1/sigma_tr [" + u + "]", [&](const DerivedChannel& c) { return c.diffuse_mfp / mm; });
  row("Burley d [" + u + "]", [&](const DerivedChannel& c) { return c.burley_d / mm; });
  row("Burley fit error", [](const DerivedChannel& c) { return c.burley_error; });
  row("surface albedo", [](const DerivedChannel& c) { return c.surface_albedo; });
  out << "physical profile: " << q.physical_model << "; object size " << from_mm(q.object_size_mm, unit) << " " << u
      << "\n";
  for (const auto& c : q.channels) {
    if (!c.model_choice.empty()) out << "  " << c.name << ": " << c.model_choice << "\n";
    bool any = false;
    for (const auto& note : c.validity)
      if (note.severity != Severity::note) out << "  " << c.name << ": " << describe(note) << "\n", any = true;
    if (!any) out << "  " << c.name << ": " << c.physical_model << " valid\n";
  }
  return out.str();
}

double object_size_mm(const std::string& text) {
  // --object-size is in mm: a physical size, independent of the output unit.
  const double v = parse_number(text, "--object-size");
  if (!(v > 0)) throw InvalidInput("--object-size", text, "> 0 (mm)");
  return v;
}

}  // namespace

Action register_materials(CLI::App& app) {
  struct Options {
    std::string db, source, format = "table", name, to, unit, output, object_size = "10", fit_file, eta,
                            import_source = "fit";
    std::string blender_method = "fixed-radius", blender_version = "auto";
    bool all = false;
  };
  auto o = std::make_shared<Options>();
  auto* sub =
      app.add_subcommand("materials", "The measured-media database: list, show, export to renderers, import fits");
  sub->require_subcommand(1);
  const auto add_db = [o](CLI::App* c) {
    c->add_option("--db", o->db, "Your own materials directory or file, added to the bundled database");
  };
  const auto add_object_size = [o](CLI::App* c) {
    c->add_option("--object-size", o->object_size,
                  "Size of the object, mm: diffusion is marked invalid where the transport mfp exceeds it [10]");
  };

  auto* list = sub->add_subcommand("list", "List materials: name, source, eta");
  add_db(list);
  list->add_option("--source", o->source, "Only materials from this source (e.g. jensen2001)");
  list->add_option("--format,-f", o->format, "table or json [table]")->check(CLI::IsMember({"table", "json"}));

  auto* show = sub->add_subcommand("show", "All coefficients, derived quantities and diffusion validity of a material");
  show->add_option("name", o->name, "Material name (case-insensitive)")->required();
  add_db(show);
  add_object_size(show);
  show->add_option("--format,-f", o->format, "table or json [table]")->check(CLI::IsMember({"table", "json"}));
  show->add_option("--unit", o->unit, "Unit of distances and coefficients: um, mm, cm, m [mm]");

  auto* exp =
      sub->add_subcommand("export", "Write materials in a renderer's form (units and conventions stated in the file)");
  auto* exp_name = exp->add_option("name", o->name, "Material name (case-insensitive)");
  auto* exp_all = exp->add_flag("--all", o->all, "Every material (with --source: every one from that source)");
  exp_name->excludes(exp_all);
  exp->add_option("--to", o->to,
                  "json, pbrt-v4, mitsuba3, blender, unity-hdrp, unity-hdrp-editor, unreal, unreal-python")
      ->required();
  exp->add_option("--unit", o->unit,
                  "Scene unit lengths and coefficients are written in: um, mm, cm, m [m; json: mm; unreal: always cm]");
  exp->add_option("--source", o->source, "With --all: only materials from this source");
  exp->add_option("--blender-method", o->blender_method,
                  "blender: Cycles subsurface method: fixed-radius (3.x Random Walk (Fixed Radius), 4.x Random Walk), "
                  "radius-remap (3.x Random Walk, 4.x Random Walk (Skin)), burley [fixed-radius]");
  exp->add_option("--blender-version", o->blender_version, "blender: 3, 4, or auto (the script picks when run) [auto]");
  exp->add_option("-o,--output", o->output, "Write to FILE (atomically) instead of stdout")->check(file_name("-o"));
  add_db(exp);
  add_object_size(exp);

  auto* imp = sub->add_subcommand("import", "Turn a 'bssrdf fit ... -f json' result into a materials file for --db");
  imp->add_option("fit", o->fit_file, "The fit result (JSON)")->required();
  imp->add_option("--name", o->name, "Name of the new material")->required();
  imp->add_option("--eta", o->eta, "Relative index [the fit's, if it fitted or recorded one]");
  imp->add_option("--source", o->import_source, "Source key of the new file [fit]");
  imp->add_option("-o,--output", o->output, "The materials file to write")->required()->check(file_name("-o"));

  return [o, list, show, exp, imp] {
    if (list->parsed()) {
      const auto db = MaterialDatabase::load_with_user(o->db);
      json out = json::array();
      std::size_t width = 0;  // the longest listed name, so the columns line up
      for (const auto& m : db.all())
        if (o->source.empty() || m.source == o->source) width = std::max(width, m.name.size());
      for (const auto& m : db.all()) {
        if (!o->source.empty() && m.source != o->source) continue;
        if (o->format == "json") {
          out.push_back({{"name", m.name},
                         {"source", m.source},
                         {"eta", m.medium.eta},
                         {"channels", m.medium.channel_names},
                         {"file", m.file}});
        } else {
          std::cout << m.name << std::string(width + 2 - m.name.size(), ' ') << m.source << "  eta " << m.medium.eta
                    << '\n';
        }
      }
      if (o->format == "json") std::cout << out.dump(2) << '\n';
    } else if (show->parsed()) {
      const auto unit = parse_length_unit(o->unit.empty() ? "mm" : o->unit, "--unit");
      DerivationOptions options;
      options.object_size_mm = object_size_mm(o->object_size);
      const auto db = MaterialDatabase::load_with_user(o->db);
      const auto& m = db.find(o->name);
      const auto q = derive_quantities(m.medium, options);
      for (const auto& c : q.channels) warn_validity(c.physical_model, c.name, c.validity);
      std::cout << (o->format == "json" ? show_json(m, q, unit).dump(2) + "\n" : show_table(m, q, unit));
    } else if (exp->parsed()) {
      const auto target = with_flag_names({{"to", "--to"}}, [&] { return parse_renderer_target(o->to); });
      if (o->name.empty() && !o->all) throw InvalidInput("materials export: give a material NAME or --all");
      const auto unit =
          parse_length_unit(o->unit.empty() ? (target == RendererTarget::json ? "mm" : "m") : o->unit, "--unit");
      DerivationOptions options;
      options.object_size_mm = object_size_mm(o->object_size);
      const auto db = MaterialDatabase::load_with_user(o->db);
      std::vector<ExportEntry> entries;
      const auto add = [&](const Material& m) {
        entries.push_back(
            {m, target == RendererTarget::json ? DerivedQuantities{} : derive_quantities(m.medium, options)});
        for (const auto& c : entries.back().derived.channels)
          warn_validity(c.physical_model, (o->all ? m.name + " " : "") + c.name, c.validity);
      };
      if (o->all) {
        for (const auto& m : db.all())
          if (o->source.empty() || m.source == o->source) add(m);
        if (entries.empty()) throw InvalidInput("--source", "'" + o->source + "'", "a source of a loaded file");
      } else {
        add(db.find(o->name));
      }
      ExportOptions export_options;
      export_options.blender_method = parse_cycles_mapping(o->blender_method, "--blender-method");
      if (o->blender_version != "auto") {
        if (o->blender_version != "3" && o->blender_version != "4")
          throw InvalidInput("--blender-version", "'" + o->blender_version + "'", "3, 4 or auto");
        export_options.blender_version = std::stoi(o->blender_version);
      }
      const std::string text = export_materials(target, entries, unit, export_options);
      if (o->output.empty())
        std::cout << text;
      else
        write_file_atomically(o->output, text);
    } else if (imp->parsed()) {
      const std::optional<double> eta =
          o->eta.empty() ? std::nullopt : std::optional<double>(parse_number(o->eta, "--eta"));
      const std::string text = materials_file_from_fit(read_data_file(o->fit_file, "the fit result"), o->fit_file,
                                                       o->name, eta, o->import_source);
      MaterialDatabase().add_text(text, o->output);  // validate it as the file it becomes, before anything is written
      write_file_atomically(o->output, text);
      std::cout << "written: " << o->output << " (load it with --db " << o->output << ")\n";
    }
  };
}

}  // namespace bssrdf::cli
