// 'bssrdf materials show': a material's coefficients, derived quantities and validity, as JSON or a table.
#pragma once

#include <string>

#include "bssrdf/derived_quantities.hpp"
#include "bssrdf/materials.hpp"
#include "bssrdf/units.hpp"

namespace bssrdf::cli {

std::string show_json(const Material& m, const DerivedQuantities& q, LengthUnit unit);
std::string show_table(const Material& m, const DerivedQuantities& q, LengthUnit unit);

}  // namespace bssrdf::cli
