// bssrdf skin: the two-layer skin model's spectral layers, total reflectance and colour; bssrdf fit skin: its
// parameters from a measured reflectance spectrum (--spectrum) or a target colour (--srgb).
#include <cmath>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bssrdf/error.hpp"
#include "bssrdf/fit/skin_fit.hpp"
#include "bssrdf/io/atomic_file.hpp"
#include "bssrdf/io/layers_json.hpp"
#include "bssrdf/montecarlo.hpp"
#include "bssrdf/skin/skin_model.hpp"
#include "bssrdf/spectral/colour_medium.hpp"
#include "bssrdf/spectral/colour_reference.hpp"
#include "cli_common.hpp"
#include "colour_options.hpp"
#include "commands.hpp"
#include "skin_command.hpp"

namespace bssrdf::cli {
namespace {

// --melanin, --blood, ...: one option per model parameter, its range in the help.
struct SkinParameterOptions {
  std::map<std::string, std::string> given;
  void add_to(CLI::App& app, const std::string& role) {
    const skin::SkinParameters defaults;
    for (const auto& r : skin::skin_parameter_ranges())
      app.add_option(std::string("--") + r.name, given[r.name],
                     role + " " + r.meaning + (r.unit[0] ? std::string(", ") + r.unit : std::string()) + ", " +
                         format_number(r.min) + " to " + format_number(r.max) + " [" +
                         format_number(defaults.*r.member) + "]");
  }
  skin::SkinParameters resolve() const {
    skin::SkinParameters p;
    for (const auto& r : skin::skin_parameter_ranges())
      if (const auto& text = given.at(r.name); !text.empty())
        p.*r.member = parse_number(text, std::string("--") + r.name);
    try {
      p.validate();
    } catch (const InvalidInput& e) {
      throw InvalidInput("--" + e.field(), e.value(), e.accepted());
    }
    return p;
  }
};

bool parse_specular(const std::string& text) {
  if (text == "included") return true;
  if (text == "excluded") return false;
  throw InvalidInput("--specular", "'" + text + "'", "included or excluded");
}

std::string csv_columns(const std::vector<double>& nm,
                        const std::vector<std::pair<std::string, std::vector<double>>>& columns) {
  std::ostringstream out;
  out << "wavelength_nm";
  for (const auto& c : columns) out << ',' << c.first;
  out << '\n';
  for (std::size_t i = 0; i < nm.size(); ++i) {
    out << format_number(nm[i]);
    for (const auto& c : columns) out << ',' << format_number(c.second[i]);
    out << '\n';
  }
  return out.str();
}

std::vector<double> default_wavelengths() {
  std::vector<double> nm;
  for (int l = 380; l <= 780; l += 10) nm.push_back(l);
  return nm;
}

}  // namespace

Action register_skin(CLI::App& app) {
  struct Options {
    SkinParameterOptions parameters;
    ColourOptions colour;
    OutputOptions output;
    std::string wavelengths, specular = "excluded", layers_out;
    std::uint64_t profile_photons = 0;  // 0: no profile
  };
  auto o = std::make_shared<Options>();
  auto* sub = app.add_subcommand("skin",
                                 "Two-layer human skin (melanin epidermis over blood dermis): spectral layers, "
                                 "total reflectance (adding-doubling) and its colour");
  o->parameters.add_to(*sub, "Skin:");
  sub->add_option("--wavelengths", o->wavelengths, "Wavelengths in nm, 250-1000, increasing [380,390,...,780]");
  o->colour.add_to(*sub);
  sub->add_option("--specular", o->specular,
                  "Whether the colour includes the surface's specular reflection: included or excluded [excluded: a "
                  "renderer adds its own]");
  sub->add_option("--layers-out", o->layers_out,
                  "Write the layer stack (bssrdf-layers JSON, channels by wavelength) "
                  "for 'bssrdf reference --layers' and 'bssrdf profile --layers'")
      ->check(file_name("--layers-out"));
  add_count_option(*sub, "--profile-photons", o->profile_photons, 1, kMaxPhotons,
                   "Also the colour radial profile: Monte Carlo of the layers with this many photons per wavelength, "
                   "integrated per bin to --colour ('profile' in -f json) [off]");
  o->output.add_to(*sub);
  return [o] {
    const auto p = o->parameters.resolve();
    const auto nm = o->wavelengths.empty() ? default_wavelengths() : parse_number_list(o->wavelengths, "--wavelengths");
    const bool specular = parse_specular(o->specular);
    const auto stack = with_flag_names({{"wavelength", "--wavelengths"}}, [&] { return skin::skin_stack(p, nm); });
    Medium carrier;  // only its wavelengths: --colour needs a spectral medium
    carrier.wavelength_nm = nm;
    const auto settings = o->colour.resolve(carrier).value_or(spectral::ColourSettings{});
    const auto reflectance = skin::skin_reflectance(p, nm);
    const auto total = reflectance.total(specular);
    const spectral::ColourIntegrator colour(nm, settings);
    const auto rgb = colour.rgb(total);
    nlohmann::json doc;
    doc["model"] = "two-layer skin: epidermis (melanin) over a semi-infinite dermis (blood, water), adding-doubling";
    for (const auto& r : skin::skin_parameter_ranges()) doc["parameters"][r.name] = p.*r.member;
    doc["wavelength_nm"] = nm;
    doc["epidermis"] = {{"thickness_mm", p.epidermis_mm},
                        {"sigma_a", stack.layers[0].sigma_a},
                        {"sigma_s", stack.layers[0].sigma_s},
                        {"g", p.g}};
    doc["dermis"] = {{"sigma_a", stack.layers[1].sigma_a}, {"sigma_s", stack.layers[1].sigma_s}, {"g", p.g}};
    doc["diffuse_reflectance"] = reflectance.diffuse;
    doc["specular_reflectance"] = reflectance.specular;
    doc["colour"] = {{"observer", std::string(spectral::kObserverName)},
                     {"illuminant", std::string(spectral::to_string(settings.illuminant))},
                     {"space", std::string(spectral::to_string(settings.space))},
                     {"specular_included", specular},
                     {"rgb", rgb}};
    doc["error"] = "adding-doubling totals within 1e-4 (its angle-doubling estimate)";
    std::ostringstream table;
    table << "skin      " << nm.size() << " wavelengths " << format_number(nm.front()) << "-"
          << format_number(nm.back()) << " nm, adding-doubling totals (error < 1e-4)\n";
    for (const auto& r : skin::skin_parameter_ranges())
      table << "  " << r.name << " = " << format_number(p.*r.member) << " " << r.unit << "\n";
    table << "colour    " << spectral::to_string(settings.space) << " under "
          << spectral::to_string(settings.illuminant) << " (" << (specular ? "specular included" : "diffuse only")
          << "): " << format_number(rgb[0]) << ", " << format_number(rgb[1]) << ", " << format_number(rgb[2]) << "\n";
    table << "\n  nm     epidermis mu_a  dermis mu_a  mu_s' (1/mm)  R_diffuse\n";
    for (std::size_t i = 0; i < nm.size(); ++i)
      table << "  " << format_number(nm[i]) << "    " << format_number(stack.layers[0].sigma_a[i]) << "    "
            << format_number(stack.layers[1].sigma_a[i]) << "    "
            << format_number(stack.layers[1].sigma_s[i] * (1 - p.g)) << "    " << format_number(reflectance.diffuse[i])
            << "\n";
    if (o->profile_photons) {  // the colour R(r): each wavelength's Monte Carlo profile, integrated per bin
      MonteCarloOptions mc;
      mc.photons = o->profile_photons;
      mc.progress = progress_bar("skin profile");
      const auto result = spectral::colour_reference(run_monte_carlo(stack, mc), nm, settings);
      doc["profile"] = nlohmann::json::parse(
          spectral::colour_reference_json(result, LengthUnit::millimetre, spectral::colour_note(nm, settings)));
      const auto diffuse = colour.rgb(reflectance.diffuse);  // Monte Carlo's R_d leaves the specular out
      table << "profile   Monte Carlo, " << mc.photons << " photons per wavelength (R(r) per bin: -f json); its "
            << "diffuse totals R, G, B (+- 1 standard error) against adding-doubling's:";
      const auto five = [](double x) { return format_number(std::round(x * 1e5) / 1e5); };
      for (int c = 0; c < 3; ++c)
        table << (c ? "," : "") << " " << five(result.channels[c].diffuse_reflectance.value) << " +- "
              << five(result.channels[c].diffuse_reflectance.standard_error) << " (" << five(diffuse[c]) << ")";
      table << "\n";
    }
    if (!o->layers_out.empty()) write_file_atomically(o->layers_out, layers_json(stack));
    emit(
        o->output, [&] { return doc.dump(2) + "\n"; },
        [&] {
          return csv_columns(
              nm, {{"diffuse_reflectance", reflectance.diffuse}, {"specular_reflectance", reflectance.specular}});
        },
        table.str());
  };
}

FitSkinCommand register_fit_skin(CLI::App& fit) {
  struct Options {
    SkinParameterOptions start;
    OutputOptions output;
    std::string spectrum, column, srgb, specular = "included", min_nm = "400", max_nm = "1000", solve_step = "20";
    bool linear = false;
  };
  auto o = std::make_shared<Options>();
  auto* sub = fit.add_subcommand("skin",
                                 "Two-layer skin parameters from a total reflectance spectrum (--spectrum) or a "
                                 "target colour (--srgb)");
  auto* spectrum = sub->add_option("--spectrum", o->spectrum,
                                   "Measured total reflectance: text table, wavelength (nm) then reflectance columns");
  sub->add_option("--column", o->column, "Which reflectance column (name or number) [the first]");
  auto* srgb = sub->add_option("--srgb", o->srgb, "Target colour R,G,B, display-encoded sRGB in 0-1 (or --linear)");
  spectrum->excludes(srgb);
  sub->add_flag("--linear", o->linear, "--srgb is linear sRGB, not display-encoded");
  sub->add_option("--specular", o->specular,
                  "Whether the measurement includes the specular reflection: included (8-degree/hemispherical "
                  "spheres, NIST's skin data) or excluded [included]");
  sub->add_option("--min-nm", o->min_nm, "Shortest wavelength fitted [400]");
  sub->add_option("--max-nm", o->max_nm, "Longest wavelength fitted [1000]");
  sub->add_option("--solve-step", o->solve_step, "Spacing (nm) of the wavelengths the solver uses [20]");
  o->start.add_to(*sub, "Start value / fixed value of the");
  o->output.add_to(*sub);
  return {sub, [o] {
            SkinFitOptions options;
            options.start = o->start.resolve();
            options.specular_included = parse_specular(o->specular);
            options.min_nm = parse_number(o->min_nm, "--min-nm");
            options.max_nm = parse_number(o->max_nm, "--max-nm");
            options.solve_step_nm = parse_number(o->solve_step, "--solve-step");
            if (!(options.max_nm > options.min_nm))
              throw InvalidInput("--max-nm", o->max_nm, "> --min-nm = " + o->min_nm);
            if (!(options.solve_step_nm >= 0 && options.solve_step_nm <= 100))
              throw InvalidInput("--solve-step", o->solve_step, "0 to 100 nm");
            SkinFitResult result;
            if (!o->spectrum.empty()) {
              const auto data =
                  with_flag_names({{"column", "--column"}}, [&] { return read_spectrum(o->spectrum, o->column); });
              result = with_flag_names({{"spectrum", "--spectrum"}}, [&] { return fit_skin_spectrum(data, options); });
            } else if (!o->srgb.empty()) {
              const auto v = parse_number_list(o->srgb, "--srgb");
              if (v.size() != 3) throw InvalidInput("--srgb", o->srgb, "three values R,G,B");
              spectral::Vec3 linear;
              for (int k = 0; k < 3; ++k) {
                if (!(v[k] > 0 && v[k] < 1)) throw InvalidInput("--srgb", format_number(v[k]), "0 < value < 1");
                linear[k] = o->linear ? v[k] : spectral::srgb_to_linear(v[k]);
              }
              result = fit_skin_colour(linear, options);
              result.source = "srgb " + o->srgb + (o->linear ? " (linear)" : " (encoded)");
            } else {
              throw InvalidInput("fit skin: give --spectrum FILE or --srgb R,G,B");
            }
            emit(
                o->output, [&] { return result.to_json(); },
                [&] {
                  return csv_columns(result.wavelength_nm, {{"measured", result.measured}, {"fitted", result.fitted}});
                },
                result.to_table());
          }};
}

}  // namespace bssrdf::cli
