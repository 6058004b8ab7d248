// bssrdf: diffusion profiles, Monte Carlo references, fits and lookup tables for subsurface
// scattering. A thin shell over the library: parse, validate at the edge, call, print.
#include <glog/logging.h>
#include <malloc.h>
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "bssrdf/error.hpp"
#include "bssrdf/text.hpp"
#include "bssrdf/units.hpp"
#include "commands.hpp"
#include "launched_process_group.hpp"

namespace {

using bssrdf::printable;

// Enum-like values (models, formats, units, kinds, targets) are case-insensitive on every command:
// lower-cased here, once, before any command sees them. File names and material names are left alone.
void lower_enum_values(int argc, char** argv) {
  static const char* const kEnumOptions[] = {"--model",
                                             "--format",
                                             "-f",
                                             "--unit",
                                             "--kind",
                                             "-k",
                                             "--to",
                                             "--convention",
                                             "--loss",
                                             "--layout",
                                             "--interpolation",
                                             "--blender-method",
                                             "--blender-version",
                                             "--reference",
                                             "--target",
                                             "--spacing",
                                             "--bin-spacing",
                                             "--absorption",
                                             "--incidence"};
  const auto lower = [](char* text) {
    for (; *text; ++text) *text = static_cast<char>(std::tolower(static_cast<unsigned char>(*text)));
  };
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    for (const char* name : kEnumOptions) {
      const std::string option = name;
      if (arg == option && i + 1 < argc) {
        lower(argv[i + 1]);
      } else if (arg.rfind(option + "=", 0) == 0) {
        lower(argv[i] + option.size() + 1);
      }
    }
  }
}

// The command the user reached: the deepest parsed subcommand.
CLI::App* parsed_command(CLI::App& app) {
  for (auto* sub : app.get_subcommands({}))
    if (sub->parsed()) return parsed_command(*sub);
  return &app;
}

// CLI11's parse errors made helpful: an unknown option gets the nearest option of that command (also
// when it hides behind another error, e.g. "--too json" behind "--to is required"); with `extras`
// ("arguments were not expected"), a unit typed as a separate word ("--pixel 1 mm") gets the
// spelling meant.
std::string explain(CLI::App& app, int argc, char** argv, const std::string& message, bool extras) {
  CLI::App* command = parsed_command(app);
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const std::string name = arg.substr(0, arg.find('='));
    if (arg.size() > 1 && arg[0] == '-' && !std::isdigit(static_cast<unsigned char>(arg[1])) && arg[1] != '.' &&
        !command->get_option_no_throw(name)) {
      std::string best;
      std::size_t best_distance = 4;  // further than 3 edits is not a typo
      for (const auto* option : command->get_options())
        for (const auto& long_name : option->get_lnames())
          if (const auto d = bssrdf::edit_distance(name, "--" + long_name); d < best_distance)
            best_distance = d, best = "--" + long_name;
      return "unknown option '" + printable(name) + "' for '" + command->get_name() + "'" +
             (best.empty() ? "; see 'bssrdf " + command->get_name() + " --help'" : "; did you mean '" + best + "'?");
    }
    if (!extras) continue;
    try {
      bssrdf::parse_length_unit(arg);
    } catch (const bssrdf::InvalidInput&) {
      continue;
    }
    const auto is_number = [](const char* text) {
      char* end = nullptr;
      std::strtod(text, &end);
      return end != text && *end == '\0';
    };
    if (i >= 3 && argv[i - 2][0] == '-' &&
        std::isalpha(static_cast<unsigned char>(argv[i - 2][1] == '-' ? argv[i - 2][2] : argv[i - 2][1])) &&
        is_number(argv[i - 1])) {  // "--pixel 1 mm": OPTION NUMBER UNIT
      const std::string option = argv[i - 2];
      const auto* known = command->get_option_no_throw(option);
      const bool takes_unit = known && known->get_description().find("optional unit") != std::string::npos;
      return "'" + printable(arg) + "' was not expected: " +
             (takes_unit ? "write the unit joined to the number, '" + option + " " + argv[i - 1] + arg + "'"
                         : option + " is in --unit; give '--unit " + arg + "'");
    }
  }
  return message;
}

// Freed memory stays with the process for the next allocation: glibc otherwise maps every block above
// 128 KB afresh and hands freed heap tops back, so each table of a batch (`lut --all` encodes 47 of up to
// 0.8 MB) touches new pages, a page fault each (4 KB), which cost the penumbra batch half its time.
void keep_freed_memory() {
#ifdef __GLIBC__
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's largest: blocks up to 32 MB come from the heap
  mallopt(M_TRIM_THRESHOLD, 128 << 20);
#endif
}

}  // namespace

int main(int argc, char** argv) {
  keep_freed_memory();
  bssrdf::prepare_launched_process();  // under mpirun or srun, rank 0 alone speaks (docs/mpi.md)
  // Ceres logs through glog; the tool reports solver outcomes itself, so keep glog quiet.
  google::InitGoogleLogging(argv[0]);
  FLAGS_minloglevel = google::GLOG_FATAL;
  FLAGS_logtostderr = true;
  CLI::App app{"bssrdf " BSSRDF_VERSION
               ": subsurface-scattering diffusion profiles, references, fits and lookup tables.\n"
               "Run 'bssrdf COMMAND --help' for a command's options."};
  app.set_version_flag("--version", std::string("bssrdf ") + BSSRDF_VERSION);
  app.require_subcommand(1);
  app.fallthrough(false);

  std::map<CLI::App*, bssrdf::cli::Action> actions;
  for (auto* register_command :
       {&bssrdf::cli::register_profile, &bssrdf::cli::register_models, &bssrdf::cli::register_materials,
        &bssrdf::cli::register_reference, &bssrdf::cli::register_fit, &bssrdf::cli::register_transmission,
        &bssrdf::cli::register_lut, &bssrdf::cli::register_slab, &bssrdf::cli::register_advise,
        &bssrdf::cli::register_skin}) {
    const auto before = app.get_subcommands({});
    auto action = (*register_command)(app);
    for (auto* sub : app.get_subcommands({}))
      if (std::find(before.begin(), before.end(), sub) == before.end()) actions[sub] = action;
  }

  if (argc > 1 && argv[1][0] != '-') {
    bool known = false;
    std::string names;
    for (auto* sub : app.get_subcommands({})) {
      known |= sub->get_name() == argv[1];
      names += (names.empty() ? "" : ", ") + sub->get_name();
    }
    if (!known) {
      std::cerr << "bssrdf: error: unknown command '" << printable(argv[1]) << "'; commands: " << names << "\n";
      return 2;
    }
  }
  lower_enum_values(argc, argv);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);  // --help, --version
  } catch (const CLI::ExtrasError& e) {
    std::cerr << "bssrdf: error: " << explain(app, argc, argv, printable(e.what()), true) << "\n";
    return 2;
  } catch (const CLI::ParseError& e) {
    std::cerr << "bssrdf: error: " << explain(app, argc, argv, printable(e.what()), false) << "\n";
    return 2;
  } catch (const bssrdf::InvalidInput& e) {  // a count option's range check (add_count_option)
    std::cerr << "bssrdf: error: " << printable(e.what()) << "\n";
    return 2;
  }
  try {
    for (auto* sub : app.get_subcommands()) {
      // Nested subcommands (e.g. "materials list") register their own actions on the child.
      auto it = actions.find(sub);
      if (it != actions.end()) it->second();
    }
  } catch (const bssrdf::InvalidInput& e) {
    std::cerr << "bssrdf: error: " << printable(e.what()) << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "bssrdf: internal error: " << printable(e.what()) << "\n";
    return 1;
  }
  return 0;
}
