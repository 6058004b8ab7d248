// The compiled part of the `bssrdf` Python package (python/bssrdf/__init__.py re-exports it).
#include "bindings.hpp"
#include "bssrdf/error.hpp"

#ifndef BSSRDF_VERSION
#define BSSRDF_VERSION "unknown"
#endif

PYBIND11_MODULE(_bssrdf, m) {
  m.doc() = "bssrdf: subsurface-scattering profiles, references, fits and lookup tables (compiled core)";
  m.attr("__version__") = BSSRDF_VERSION;
  // Bad input is a ValueError with the command line's one-line message (control bytes from the input,
  // a newline in a name, shown as \xHH as the CLI prints them).
  pybind11::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const bssrdf::InvalidInput& e) {
      PyErr_SetString(PyExc_ValueError, bssrdf::printable(e.what()).c_str());
    }
  });
  bssrdf::python::bind_medium(m);
  bssrdf::python::bind_profile(m);
  bssrdf::python::bind_reference(m);
  bssrdf::python::bind_tables(m);
}
