// The three forms of an .rxt inversion: JSON {"rows": [...]} with the file's header echoed, CSV
// and a table for people.
#pragma once

#include <string>

#include "bssrdf/fit/rxt_fit.hpp"

namespace bssrdf::cli {

std::string rxt_fit_json(const RxtFit& fit);
std::string rxt_fit_csv(const RxtFit& fit);
std::string rxt_fit_table(const RxtFit& fit);

}  // namespace bssrdf::cli
