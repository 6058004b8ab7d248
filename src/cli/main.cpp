// bssrdf: diffusion profiles, Monte Carlo references, fits and lookup tables for subsurface
// scattering. A thin shell over the library: parse, validate at the edge, call, print.
#include <glog/logging.h>
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <exception>
#include <iostream>
#include <map>
#include <string>

#include "bssrdf/error.hpp"
#include "commands.hpp"
#include "launched_process_group.hpp"

namespace {

// A message for the terminal: control bytes from input files (a CR in a CSV field, an escape
// sequence) are shown as \xHH instead of acting on the terminal, so errors stay one visible line.
std::string printable(const std::string& message) {
  std::string out;
  for (const unsigned char c : message) {
    if (c >= 0x20 && c != 0x7f) {
      out += static_cast<char>(c);
    } else {
      char hex[5];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
    }
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
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
        &bssrdf::cli::register_lut, &bssrdf::cli::register_slab, &bssrdf::cli::register_advise}) {
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
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);  // --help, --version
  } catch (const CLI::ParseError& e) {
    std::cerr << "bssrdf: error: " << printable(e.what()) << "\n";
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
