// bssrdf materials list | show | export | import: the measured-media database, what each entry
// implies (derived quantities, diffusion validity), renderer exports, and fitted materials saved
// in the database's own format.
#include <unistd.h>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
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
#include "bssrdf/spectral/colour_medium.hpp"
#include "cli_common.hpp"
#include "colour_options.hpp"
#include "commands.hpp"
#include "materials_show.hpp"

namespace bssrdf::cli {
namespace {

using json = nlohmann::ordered_json;

// 'materials import': the new file is -o FILE, or NAME.json in the --db directory (created if absent,
// never written over); either way it is validated against the database it joins before it is written.
void import_fit(const std::string& fit_file, const std::string& name, const std::string& eta_text,
                const std::string& source, const std::string& output, const std::string& db) {
  namespace fs = std::filesystem;
  const std::optional<double> eta = eta_text.empty() ? std::nullopt : std::optional(parse_number(eta_text, "--eta"));
  std::vector<std::string> skipped;  // fit slab --rxt rows that did not converge
  const std::string text =
      materials_file_from_fit(read_data_file(fit_file, "the fit result"), fit_file, name, eta, source, &skipped);
  std::string target = output;
  if (target.empty()) {
    if (db.empty()) throw InvalidInput("materials import: give --db DIR (your materials directory) or -o FILE");
    std::error_code ec;
    if (fs::exists(db, ec) && !fs::is_directory(db, ec))
      throw InvalidInput("--db", "'" + db + "'", "a directory (or choose the file with -o FILE)");
    std::string stem;
    for (const char c : name)
      stem += std::isalnum(static_cast<unsigned char>(c)) ? static_cast<char>(std::tolower(c)) : '-';
    target = (fs::path(db) / (stem + ".json")).string();
    if (fs::exists(target, ec))
      throw InvalidInput("--name", "'" + name + "'", "a name whose file " + target + " does not exist yet");
  }
  std::error_code ec;
  auto database = MaterialDatabase::load_with_user(fs::is_directory(db, ec) ? db : "");
  database.add_text(text, target);  // a valid file whose name clashes with no loaded material
  if (output.empty()) fs::create_directories(db);
  write_file_atomically(target, text);
  if (!skipped.empty())
    std::cerr << "bssrdf: skipped " << skipped.size() << " row" << (skipped.size() > 1 ? "s" : "")
              << " that did not converge (listed in the file's notes), first " << skipped.front() << '\n';
  std::cout << "written: " << target << " (use it with --db " << (output.empty() ? db : target) << ")\n";
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
    MediumOptions inline_medium;  // materials export with --sigma-a ...: a medium not in the database
    ColourOptions colour;         // materials export of spectral materials to R, G, B
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
                  "Size of the object, mm: a channel whose transport mfp exceeds it gets a warning (object_size: "
                  "light leaves before it becomes diffuse; a semi-infinite profile misstates the object) [10]");
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
  auto* exp_name =
      exp->add_option("name", o->name, "Material name (case-insensitive); with --sigma-a: the new material's name");
  auto* exp_all = exp->add_flag("--all", o->all, "Every material (with --source: every one from that source)");
  exp_name->excludes(exp_all);
  o->inline_medium.add_coefficients_to(*exp);  // as 'bssrdf profile' takes them; their unit is --unit [mm]
  o->colour.add_to(*exp);                      // spectral materials to RGB targets: srgb under d65 unless given
  exp_all->excludes(exp->get_option("--sigma-a"));
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

  auto* imp = sub->add_subcommand("import", "Turn a 'bssrdf fit ... -f json' result into a material in your --db");
  imp->add_option("fit", o->fit_file, "The fit result (JSON of fit profile, albedo, slab or slab --rxt)")->required();
  imp->add_option("--name", o->name, "Name of the new material")->required();
  imp->add_option("--eta", o->eta, "Relative index [the fit's]");
  imp->add_option("--source", o->import_source, "Source key of the new file [fit]");
  imp->add_option("--db", o->db, "Your materials directory: the material is written there as NAME.json");
  imp->add_option("-o,--output", o->output, "The materials file to write instead")->check(file_name("-o"));

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
      std::cout << (o->format == "json" ? show_json(m, q, unit) : show_table(m, q, unit));
    } else if (exp->parsed()) {
      const auto target = with_flag_names({{"to", "--to"}}, [&] { return parse_renderer_target(o->to); });
      const auto& inline_medium = o->inline_medium;
      const bool own = !inline_medium.sigma_a.empty() || !inline_medium.sigma_s.empty() ||
                       !inline_medium.sigma_s_prime.empty() || !inline_medium.g.empty() || !inline_medium.eta.empty();
      if (o->name.empty() && !o->all && !own)
        throw InvalidInput("materials export: give a material NAME, --all, or a medium (--sigma-a ...)");
      const auto unit =
          parse_length_unit(o->unit.empty() ? (target == RendererTarget::json ? "mm" : "m") : o->unit, "--unit");
      DerivationOptions options;
      options.object_size_mm = object_size_mm(o->object_size);
      const auto db = MaterialDatabase::load_with_user(o->db);
      std::vector<ExportEntry> entries;
      const bool colour_given = !o->colour.colour.empty() || !o->colour.illuminant.empty();
      if (colour_given && target == RendererTarget::json)
        throw InvalidInput("--colour: not with --to json (it keeps a spectral material's wavelengths; it loads back)");
      const auto add = [&](Material m) {
        std::string colour;  // a spectral material for an RGB target (pbrt-v4 takes spectra): its colour stand-in
        if (colour_given && !o->all) o->colour.resolve(m.medium);  // refuses a material without wavelengths
        if (m.medium.spectral() &&
            (colour_given || (target != RendererTarget::json && target != RendererTarget::pbrt_v4))) {
          auto settings = o->colour.resolve(m.medium).value_or(spectral::ColourSettings{});
          auto stand_in = spectral::colour_material(m, settings);
          m = stand_in.material;
          colour = "colour: " + stand_in.colour.summary() +
                   (colour_given ? "" : " (the default colour; give --colour and --illuminant to choose)");
        }
        entries.push_back(
            {m, target == RendererTarget::json ? DerivedQuantities{} : derive_quantities(m.medium, options)});
        entries.back().derived.colour = colour;
        for (const auto& c : entries.back().derived.channels)
          warn_validity(c.physical_model, (o->all ? m.name + " " : "") + c.name, c.validity);
      };
      if (o->all) {
        for (const auto& m : db.all())
          if (o->source.empty() || m.source == o->source) add(m);
        if (entries.empty()) throw InvalidInput("--source", "'" + o->source + "'", "a source of a loaded file");
      } else if (own) {  // coefficients in --unit (mm when not given), as 'bssrdf profile' reads them
        auto medium = inline_medium;
        medium.unit = o->unit.empty() ? "mm" : o->unit;
        const auto resolved = medium.resolve();
        add(Material{o->name.empty() ? "custom" : o->name,
                     "command-line",
                     "given on the bssrdf command line",
                     "",
                     resolved.unit,
                     false,
                     resolved.medium,
                     {}});
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
      import_fit(o->fit_file, o->name, o->eta, o->import_source, o->output, o->db);
    }
  };
}

}  // namespace bssrdf::cli
