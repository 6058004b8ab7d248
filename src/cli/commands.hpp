// One function per subcommand: `register_X` adds the subcommand and its options to the app and
// returns the action to run after parsing.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace bssrdf::cli {

using Action = std::function<void()>;

Action register_profile(CLI::App& app);
Action register_models(CLI::App& app);
Action register_materials(CLI::App& app);
Action register_reference(CLI::App& app);
Action register_fit(CLI::App& app);
Action register_transmission(CLI::App& app);
Action register_lut(CLI::App& app);
Action register_slab(CLI::App& app);
Action register_advise(CLI::App& app);
Action register_skin(CLI::App& app);

}  // namespace bssrdf::cli
