// bssrdf advise: the cheapest representation of a material that looks right at a pixel size
// (advise/advise.hpp), for one medium or (--all) every material of the database.
#include <cctype>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "bssrdf/advise/advise.hpp"
#include "bssrdf/advise/advise_files.hpp"
#include "bssrdf/advise/auto_reference.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/image/reference_profile.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/parallel.hpp"
#include "bssrdf/validity.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace bssrdf::cli {
namespace {

// "0.1", "0.1mm", "20 um", "5cm": a length in mm; a bare number is in `unit`.
double parse_length(const std::string& text, const std::string& field, LengthUnit unit) {
  std::size_t end = text.size();
  while (end > 0 && std::isalpha(static_cast<unsigned char>(text[end - 1]))) --end;
  std::string number = text.substr(0, end), suffix = text.substr(end);
  while (!number.empty() && number.back() == ' ') number.pop_back();
  if (!suffix.empty()) {
    try {
      unit = parse_length_unit(suffix, field);
    } catch (const InvalidInput&) {
      throw InvalidInput(field, text, "a length > 0 with an optional unit um, mm, cm or m (e.g. 0.1mm)");
    }
  }
  const double value = parse_number(number, field);
  if (!(value > 0) || !std::isfinite(value))
    throw InvalidInput(field, text, "a length > 0 with an optional unit um, mm, cm or m (e.g. 0.1mm)");
  return to_mm(value, unit);
}

}  // namespace

Action register_advise(CLI::App& app) {
  struct Options {
    MediumOptions medium;
    std::string pixel, target = "any", tolerance = "1", object_size, format, write, reference = "auto";
    bool all = false;
    std::uint64_t photons = 200'000, seed = 1;
    unsigned threads = 0;
  };
  auto options = std::make_shared<Options>();
  auto* sub = app.add_subcommand(
      "advise",
      "The cheapest representation that looks right at a pixel size: every candidate's image-space "
      "error (8-bit sRGB code values at a shadow edge and a one-pixel light line) against the reference");
  options->medium.add_to(*sub);
  sub->add_option("--pixel", options->pixel,
                  "Pixel footprint on the surface, with an optional unit (0.1mm, 20um); bare: --unit")
      ->required();
  sub->add_option("--tolerance", options->tolerance, "Largest acceptable image error, 8-bit sRGB code values [1]");
  sub->add_option("--target", options->target, "realtime, offline or any [any]");
  sub->add_option("--object-size", options->object_size,
                  "Size of the object, with an optional unit: flags profiles wider than it");
  sub->add_flag("--all", options->all, "Every material of the database, one line each");
  sub->add_option("--write", options->write,
                  "Write the chosen representation's table into this directory (bssrdf-lut JSON)")
      ->check(file_name("--write"));
  sub->add_option("--reference", options->reference,
                  "What candidates are judged against: exact (the tabulated transport solution), montecarlo (a run per "
                  "material), or auto: per channel exact inside its table, else the adding-doubling total with the "
                  "best measured shape (alpha' above it) or a Monte Carlo run of the channel [auto]")
      ->check(CLI::IsMember({"auto", "exact", "montecarlo"}));
  add_count_option(*sub, "--photons,-n", options->photons, 1000, kMaxPhotons,
                   "Monte Carlo reference: photons per channel [200000]");
  add_count_option(*sub, "--seed", options->seed, 0, kMaxSeed, "Monte Carlo reference: random seed [1]");
  add_count_option(*sub, "--threads,-j", options->threads, 0, kMaxThreads,
                   "Worker threads, 0 = all cores; never changes the result [0]");
  sub->add_option("--format,-f", options->format, "table or json [table]")->check(CLI::IsMember({"table", "json"}));

  return [options] {
    const auto& o = *options;
    const LengthUnit unit = parse_length_unit(o.medium.unit, "--unit");
    AdviseOptions a;
    a.pixel = parse_length(o.pixel, "--pixel", unit);
    a.tolerance = parse_number(o.tolerance, "--tolerance");
    if (!(a.tolerance > 0) || !std::isfinite(a.tolerance))
      throw InvalidInput("--tolerance", o.tolerance, "> 0 (8-bit sRGB code values)");
    a.target = parse_advise_target(o.target);
    if (!o.object_size.empty()) a.object_size = parse_length(o.object_size, "--object-size", unit);
    const MonteCarloReference monte_carlo({o.photons, o.seed, o.threads});
    const ModelReference exact(make_model("exact"));
    const auto exact_model = make_model("exact");
    const AutoReference automatic({o.photons, o.seed, o.threads});
    // auto: per channel, exact inside its table, else adding-doubling + a measured shape or a Monte Carlo
    // run of that channel (auto_reference.hpp); exact: refuses media outside the table.
    const auto reference_for = [&](const Medium& medium) -> const ReferenceProfile& {
      if (o.reference == "montecarlo") return monte_carlo;
      if (o.reference == "auto") return automatic;
      for (std::size_t c = 0; c < medium.channels(); ++c)
        if (const auto report = exact_model->validity(medium.reduced(c)); worst(report) == Severity::invalid)
          throw InvalidInput("--reference", "exact",
                             "media inside the exact table (channel " + medium.channel_names[c] + ": " +
                                 report.front().message + "); use --reference auto or montecarlo");
      return exact;
    };
    const bool json = o.format == "json";

    if (o.all) {
      if (!o.write.empty()) throw InvalidInput("--write", o.write, "one material at a time (not with --all)");
      if (!o.medium.material.empty() || !o.medium.sigma_a.empty() || !o.medium.sigma_s.empty())
        throw InvalidInput("--all", "with a medium", "alone (it advises on every material of the database)");
      const auto database = MaterialDatabase::load_with_user(o.medium.db);
      const auto& materials = database.all();
      std::vector<std::optional<Advice>> advices(materials.size());  // in parallel, printed in order
      parallel_for(materials.size(), o.threads, [&](std::size_t i) {
        advices[i] = advise(materials[i].medium, reference_for(materials[i].medium), a);
      });
      std::ostringstream out;
      if (json)
        out << "[\n";
      else
        out << std::left << std::setw(28) << "material" << std::setw(36) << "choice" << std::right << std::setw(8)
            << "error" << std::setw(9) << "cost_ns" << std::setw(8) << "U" << std::setw(8) << "ref_s"
            << "  reference (per channel)\n";
      for (std::size_t i = 0; i < materials.size(); ++i) {
        const Advice& advice = *advices[i];
        if (json) {
          out << (i ? ",\n" : "") << to_json(advice, materials[i].name);
          continue;
        }
        const auto* c = advice.choice ? &advice.candidates[*advice.choice] : nullptr;
        std::string sources;
        for (std::size_t k = 0; k < advice.reference_sources.size(); ++k)
          sources += (k ? "," : "") + advice.reference_sources[k];
        out << std::left << std::setw(28) << materials[i].name << std::setw(36) << (c ? c->representation : "(none)")
            << std::right << std::fixed << std::setprecision(3) << std::setw(8) << (c ? c->image.error : 0.0)
            << std::setprecision(0) << std::setw(9) << (c ? c->cost : 0.0) << std::setprecision(3) << std::setw(8)
            << advice.reference_uncertainty.error() << std::setprecision(2) << std::setw(8) << advice.reference_seconds
            << "  " << sources << "\n";
      }
      if (json) out << "]\n";
      std::cout << out.str();
      return;
    }
    const auto resolved = o.medium.resolve();
    const std::string name = resolved.material ? resolved.material->name : "medium";
    const Advice advice = advise(resolved.medium, reference_for(resolved.medium), a);
    std::string written;
    if (!o.write.empty())  // before printing, so a failure prints nothing
      written =
          write_advised_file(o.write, name, resolved.medium, resolved.material, advice, {o.photons, o.seed, o.threads})
              .string();
    std::cout << (json ? to_json(advice, name) : to_table(advice, name));
    if (!written.empty() && !json) std::cout << "wrote: " << written << "\n";
  };
}

}  // namespace bssrdf::cli
