// `bssrdf fit skin` lives in skin_command.cpp beside `bssrdf skin`: fit_command.cpp runs its action when parsed.
#pragma once

#include <CLI/CLI.hpp>

#include "commands.hpp"

namespace bssrdf::cli {

struct FitSkinCommand {
  CLI::App* app;
  Action run;
};
FitSkinCommand register_fit_skin(CLI::App& fit);

}  // namespace bssrdf::cli
