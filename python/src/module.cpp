// The compiled part of the `bssrdf` Python package (python/bssrdf/__init__.py re-exports it).
#include "bindings.hpp"

#ifndef BSSRDF_VERSION
#define BSSRDF_VERSION "unknown"
#endif

PYBIND11_MODULE(_bssrdf, m) {
  m.doc() = "bssrdf: subsurface-scattering profiles, references, fits and lookup tables (compiled core)";
  m.attr("__version__") = BSSRDF_VERSION;
  bssrdf::python::bind_medium(m);
  bssrdf::python::bind_profile(m);
  bssrdf::python::bind_reference(m);
  bssrdf::python::bind_tables(m);
}
