// What the binding files share: the medium handle Python sees, numpy conversions and the helpers
// that turn a Python argument (a Medium, a Material or a material's name) into the library's types.
// The bindings hold no physics: they convert arrays and options and call the library.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "bssrdf/materials.hpp"
#include "bssrdf/medium.hpp"
#include "bssrdf/units.hpp"
#include "bssrdf/validity.hpp"

namespace bssrdf::python {

namespace py = pybind11;
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// bssrdf.Medium: coefficients in 1/mm inside, with the unit the user gave them in (the default unit
// of every output computed from it) and the database entry it came from, if any.
struct MediumHandle {
  Medium medium;
  LengthUnit unit = LengthUnit::millimetre;
  std::optional<Material> material;
};

// A Medium, a Material or a material's name (bundled database, plus `db` when given).
MediumHandle to_medium(const py::handle& object, const std::string& db = "");
// The unit of outputs: `unit` when given, else the medium's.
LengthUnit output_unit(const std::optional<std::string>& unit, const MediumHandle& medium);

// An argument as a message shows it: its repr on one line (numpy prints arrays on several), at most
// 80 characters.
std::string short_repr(const py::handle& object);
// A number, or a string passed on as the command line would take it (lut's `range`); `field` names it.
std::string number_or_text(const py::handle& object, const std::string& field);

// A 1-D float64 array from a scalar or any sequence; `field` names it in errors.
std::vector<double> to_vector(const py::handle& object, const std::string& field);
Array to_array(const std::vector<double>& values);
// rows x columns, row-major.
Array to_array(const std::vector<std::vector<double>>& rows);

// A whole-number argument in [min, max], taken as signed so that -1 is refused by name (InvalidInput: ValueError)
// instead of failing pybind11's unsigned conversion (TypeError).
std::uint64_t checked_count(std::int64_t value, const std::string& field, std::int64_t min, std::int64_t max);

// The library's validity notes as Python objects (bssrdf.ValidityNote).
py::list to_python(const ValidityReport& report);

// The database a `db` argument names: bundled only when empty.
MaterialDatabase load_database(const std::string& db);

void bind_medium(py::module_& m);
void bind_profile(py::module_& m);
void bind_reference(py::module_& m);
void bind_tables(py::module_& m);

}  // namespace bssrdf::python
