// bssrdf.Medium, bssrdf.Material, bssrdf.ValidityNote and the functions behind bssrdf.materials:
// the database, its renderer exports, the quantities a material implies and Cycles' inputs.
#include <cmath>
#include <sstream>

#include "bindings.hpp"
#include "bssrdf/derived_quantities.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/fit/fit_import.hpp"
#include "bssrdf/io/atomic_file.hpp"
#include "bssrdf/io/cycles_subsurface.hpp"
#include "bssrdf/io/renderer_export.hpp"
#include "io/data_file.hpp"

namespace bssrdf::python {

std::string short_repr(const py::handle& object) {
  std::string out;
  for (const char c : std::string(py::str(py::repr(object)))) {
    const bool space = c == ' ' || c == '\n' || c == '\r' || c == '\t';
    if (!space || (!out.empty() && out.back() != ' ')) out += space ? ' ' : c;
  }
  return out.size() > 80 ? out.substr(0, 77) + "..." : out;
}

std::string number_or_text(const py::handle& object, const std::string& field) {
  if (py::isinstance<py::str>(object)) return object.cast<std::string>();
  if (PyNumber_Check(object.ptr()) && !py::isinstance<py::bool_>(object)) {
    const double value = PyFloat_AsDouble(object.ptr());
    if (!(value == -1 && PyErr_Occurred())) return format_number(value);
    PyErr_Clear();
  }
  throw InvalidInput(field, short_repr(object), "a number or a string");
}

std::vector<double> to_vector(const py::handle& object, const std::string& field) {
  if (object.is_none()) throw InvalidInput(field + ": a number or a sequence of numbers is required, not None");
  Array array;
  try {
    array = Array::ensure(object);
  } catch (const py::error_already_set&) {
  }
  if (!array) throw InvalidInput(field, short_repr(object), "a number or a sequence of numbers");
  if (array.ndim() > 1)
    throw InvalidInput(field + ": a number or a 1-D sequence, not an array of " + std::to_string(array.ndim()) +
                       " dimensions");
  const double* data = array.data();
  return std::vector<double>(data, data + array.size());
}

Array to_array(const std::vector<double>& values) {
  Array out(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

Array to_array(const std::vector<std::vector<double>>& rows) {
  const std::size_t columns = rows.empty() ? 0 : rows.front().size();
  Array out({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(columns)});
  double* data = out.mutable_data();
  for (const auto& row : rows) data = std::copy(row.begin(), row.end(), data);
  return out;
}

std::uint64_t checked_count(std::int64_t value, const std::string& field, std::int64_t min, std::int64_t max) {
  if (value < min || value > max)
    throw InvalidInput(field, std::to_string(value), std::to_string(min) + " to " + std::to_string(max));
  return static_cast<std::uint64_t>(value);
}

py::list to_python(const ValidityReport& report) {
  py::list out;
  for (const auto& note : report) out.append(note);
  return out;
}

MaterialDatabase load_database(const std::string& db) { return MaterialDatabase::load_with_user(db); }

MediumHandle to_medium(const py::handle& object, const std::string& db) {
  if (py::isinstance<MediumHandle>(object)) return object.cast<MediumHandle>();
  if (py::isinstance<Material>(object)) {
    const auto material = object.cast<Material>();
    return {material.medium, LengthUnit::millimetre, material};
  }
  if (py::isinstance<py::str>(object)) {
    const auto material = load_database(db).find(object.cast<std::string>());
    return {material.medium, LengthUnit::millimetre, material};
  }
  throw InvalidInput("medium", short_repr(object),
                     "a bssrdf.Medium, a bssrdf.Material or a material's name");
}

LengthUnit output_unit(const std::optional<std::string>& unit, const MediumHandle& medium) {
  return unit ? parse_length_unit(*unit) : medium.unit;
}

namespace {

// One value for every channel, or one per channel (as the command line's lists).
std::vector<double> per_channel(std::vector<double> values, std::size_t channels, const std::string& field) {
  if (values.size() == 1 && channels > 1) return std::vector<double>(channels, values[0]);
  if (values.size() != channels)
    throw InvalidInput(field + ": " + std::to_string(values.size()) + " values given, but sigma_a has " +
                       std::to_string(channels) + " channels (give one value per channel, or one for all)");
  return values;
}

// Validated in the user's unit (messages quote what was typed), then converted to 1/mm.
MediumHandle make_medium(const py::object& sigma_a, const py::object& sigma_s, const py::object& g, double eta,
                         const std::string& unit, const std::optional<std::vector<std::string>>& channels) {
  MediumHandle out;
  out.unit = parse_length_unit(unit);
  Medium& medium = out.medium;
  medium.sigma_a = to_vector(sigma_a, "sigma_a");
  const std::size_t n = medium.sigma_a.size();
  if (n == 0) throw InvalidInput("sigma_a: give at least one channel (a number, or one per channel)");
  medium.sigma_s = per_channel(to_vector(sigma_s, "sigma_s"), n, "sigma_s");
  medium.g = per_channel(to_vector(g, "g"), n, "g");
  medium.eta = eta;
  medium.channel_names = channels ? *channels : default_channel_names(n);
  if (channels && channels->size() != n)
    throw InvalidInput("channels: " + std::to_string(channels->size()) + " names given, but sigma_a has " +
                       std::to_string(n) + " channels");
  medium.validate();
  for (auto& v : medium.sigma_a) v = coefficient_to_per_mm(v, out.unit);
  for (auto& v : medium.sigma_s) v = coefficient_to_per_mm(v, out.unit);
  return out;
}

// Coefficients of a medium in its own unit (1/unit).
Array in_unit(const std::vector<double>& per_mm, LengthUnit unit) {
  std::vector<double> out;
  for (double v : per_mm) out.push_back(coefficient_from_per_mm(v, unit));
  return to_array(out);
}

std::string describe_medium(const MediumHandle& h) {
  std::ostringstream s;
  const auto list = [&](const std::vector<double>& v, bool coefficient) {
    s << '[';
    for (std::size_t i = 0; i < v.size(); ++i)
      s << (i ? ", " : "") << format_number(coefficient ? coefficient_from_per_mm(v[i], h.unit) : v[i]);
    s << ']';
  };
  s << "Medium(";
  if (h.material) s << "material='" << h.material->name << "', ";
  s << "sigma_a=";
  list(h.medium.sigma_a, true);
  s << ", sigma_s=";
  list(h.medium.sigma_s, true);
  s << ", g=";
  list(h.medium.g, false);
  s << ", eta=" << format_number(h.medium.eta) << ", unit='" << symbol(h.unit) << "')";
  return s.str();
}

std::vector<ExportEntry> export_entries(const py::handle& what, RendererTarget target, double object_size,
                                        const std::string& db) {
  DerivationOptions options;
  if (!(object_size > 0 && std::isfinite(object_size)))
    throw InvalidInput("object_size", format_number(object_size), "> 0 (mm)");
  options.object_size_mm = object_size;
  std::vector<py::handle> items;
  if (py::isinstance<py::list>(what) || py::isinstance<py::tuple>(what))
    for (const auto& item : what) items.push_back(item);
  else
    items.push_back(what);
  if (items.empty()) throw InvalidInput("materials: give at least one material or medium");
  std::vector<ExportEntry> entries;
  for (const auto& item : items) {
    const auto h = to_medium(item, db);
    Material material;
    if (h.material) {
      material = *h.material;
    } else {
      material.name = "medium";
      material.source = "python";
      material.medium = h.medium;
    }
    entries.push_back(
        {material, target == RendererTarget::json ? DerivedQuantities{} : derive_quantities(material.medium, options)});
  }
  return entries;
}

}  // namespace

void bind_medium(py::module_& m) {
  py::enum_<Severity>(m, "Severity", "How much a validity note matters: note < warning < invalid.")
      .value("note", Severity::note)
      .value("warning", Severity::warning)
      .value("invalid", Severity::invalid);

  py::class_<ValidityNote>(m, "ValidityNote", "Where a model's assumptions fail: severity, a stable code, a message.")
      .def_readonly("severity", &ValidityNote::severity)
      .def_readonly("code", &ValidityNote::code, "stable identifier for scripts, e.g. 'low_albedo'")
      .def_readonly("message", &ValidityNote::message, "one line for people, with the numbers that triggered it")
      .def("__str__", [](const ValidityNote& n) { return describe(n); })
      .def("__repr__", [](const ValidityNote& n) { return "<ValidityNote " + describe(n) + ">"; });

  py::class_<MediumHandle>(m, "Medium", R"(A homogeneous scattering medium, per colour channel.

Medium(sigma_a, sigma_s, g=0, eta=1.3, unit="mm", channels=None)

sigma_a, sigma_s: absorption and scattering coefficients in 1/unit, a number or one per channel;
g: Henyey-Greenstein anisotropy (one or per channel); eta: relative index n_medium / n_outside;
unit: um, mm, cm or m -- the unit of the coefficients given and the default unit of every output
computed from this medium; channels: names (default R, G, B for three, c0, c1, ... otherwise).
Raises ValueError naming the field, the value and the accepted range.)")
      .def(py::init(&make_medium), py::arg("sigma_a"), py::arg("sigma_s"), py::arg("g") = py::float_(0.0),
           py::arg("eta") = 1.3, py::arg("unit") = "mm", py::arg("channels") = py::none())
      .def_static(
          "from_sigma_s_prime",
          [](const py::object& sigma_a, const py::object& sigma_s_prime, const py::object& g, double eta,
             const std::string& unit, const std::optional<std::vector<std::string>>& channels) {
            const auto a = to_vector(sigma_a, "sigma_a");
            const auto gs = per_channel(to_vector(g, "g"), a.size(), "g");
            auto s = per_channel(to_vector(sigma_s_prime, "sigma_s_prime"), a.size(), "sigma_s_prime");
            for (std::size_t c = 0; c < s.size(); ++c) {
              if (!(gs[c] > -1 && gs[c] < 1)) throw InvalidInput("g", format_number(gs[c]), "-1 < g < 1");
              s[c] /= 1 - gs[c];  // sigma_s' = sigma_s (1 - g)
            }
            return make_medium(py::cast(a), py::cast(s), py::cast(gs), eta, unit, channels);
          },
          py::arg("sigma_a"), py::arg("sigma_s_prime"), py::arg("g") = py::float_(0.0), py::arg("eta") = 1.3,
          py::arg("unit") = "mm", py::arg("channels") = py::none(),
          "A medium from its reduced scattering sigma_s' = sigma_s (1 - g), in 1/unit (g = 0: what "
          "diffusion models need when g is unknown).")
      .def_property_readonly(
          "sigma_a", [](const MediumHandle& h) { return in_unit(h.medium.sigma_a, h.unit); }, "1/unit, per channel")
      .def_property_readonly(
          "sigma_s", [](const MediumHandle& h) { return in_unit(h.medium.sigma_s, h.unit); }, "1/unit, per channel")
      .def_property_readonly(
          "sigma_s_prime",
          [](const MediumHandle& h) {
            std::vector<double> v;
            for (std::size_t c = 0; c < h.medium.channels(); ++c) v.push_back(h.medium.reduced(c).sigma_s_prime);
            return in_unit(v, h.unit);
          },
          "reduced scattering sigma_s (1 - g), 1/unit")
      .def_property_readonly(
          "albedo_prime",
          [](const MediumHandle& h) {
            std::vector<double> v;
            for (std::size_t c = 0; c < h.medium.channels(); ++c) v.push_back(h.medium.reduced(c).albedo_prime);
            return to_array(v);
          },
          "reduced albedo sigma_s' / (sigma_a + sigma_s')")
      .def_property_readonly(
          "transport_mfp",
          [](const MediumHandle& h) {
            std::vector<double> v;
            for (std::size_t c = 0; c < h.medium.channels(); ++c)
              v.push_back(from_mm(1 / h.medium.reduced(c).sigma_t_prime, h.unit));
            return to_array(v);
          },
          "1 / sigma_t', in unit")
      .def_property_readonly(
          "g", [](const MediumHandle& h) { return to_array(h.medium.g); }, "anisotropy, per channel")
      .def_property_readonly(
          "eta", [](const MediumHandle& h) { return h.medium.eta; }, "relative index n_medium / n_outside")
      .def_property_readonly(
          "channels", [](const MediumHandle& h) { return h.medium.channel_names; }, "channel names")
      .def_property_readonly(
          "unit", [](const MediumHandle& h) { return std::string(symbol(h.unit)); }, "unit of coefficients")
      .def_property_readonly(
          "material", [](const MediumHandle& h) { return h.material; }, "the database entry, or None")
      .def(
          "to_unit",
          [](const MediumHandle& h, const std::string& unit) {
            MediumHandle out = h;
            out.unit = parse_length_unit(unit);
            return out;
          },
          py::arg("unit"), "The same medium, reporting (and computing outputs) in another unit.")
      .def("__len__", [](const MediumHandle& h) { return h.medium.channels(); })
      .def("__repr__", &describe_medium);

  py::class_<Material>(m, "Material", "An entry of the measured-media database (coefficients in 1/mm).")
      .def_readonly("name", &Material::name)
      .def_readonly("source", &Material::source, "short key of the publication, e.g. 'jensen2001'")
      .def_readonly("citation", &Material::citation)
      .def_readonly("file", &Material::file, "the file it was loaded from")
      .def_readonly("notes", &Material::notes)
      .def_readonly("reduced_scattering_only", &Material::reduced_scattering_only,
                    "the source gave sigma_s' only (held as sigma_s with g = 0)")
      .def_property_readonly(
          "medium",
          [](const Material& mat) {
            return MediumHandle{mat.medium, LengthUnit::millimetre, mat};
          },
          "the coefficients as a bssrdf.Medium (unit mm)")
      .def_property_readonly(
          "eta", [](const Material& mat) { return mat.medium.eta; }, "relative index")
      .def("__repr__", [](const Material& mat) { return "<Material " + mat.name + " (" + mat.source + ")>"; });

  auto materials = m.def_submodule("materials", "The measured-media database (bundled, plus your own with db=).");
  materials.def(
      "get", [](const std::string& name, const std::string& db) { return load_database(db).find(name); },
      py::arg("name"), py::arg("db") = "",
      "The material by name (case-insensitive); db: your own materials directory or file, added to the bundled "
      "database. Raises ValueError listing close names when unknown.");
  materials.def(
      "list",
      [](const std::optional<std::string>& source, const std::string& db) {
        std::vector<std::string> names;
        const auto database = load_database(db);
        for (const auto& mat : database.all())
          if (!source || mat.source == *source) names.push_back(mat.name);
        return names;
      },
      py::arg("source") = py::none(), py::arg("db") = "",
      "Material names, in the database's order (bssrdf materials list).");
  materials.def(
      "all",
      [](const std::optional<std::string>& source, const std::string& db) {
        std::vector<Material> out;
        const auto database = load_database(db);
        for (const auto& mat : database.all())
          if (!source || mat.source == *source) out.push_back(mat);
        return out;
      },
      py::arg("source") = py::none(), py::arg("db") = "",
      "Every material (optionally of one source) as Material objects.");
  materials.def(
      "export",
      [](const py::object& what, const std::string& to, const std::optional<std::string>& unit,
         const std::string& blender_method, std::optional<int> blender_version, double object_size,
         const std::string& db, const std::optional<std::string>& output) {
        const auto target = parse_renderer_target(to);
        const auto u = parse_length_unit(unit ? *unit : (target == RendererTarget::json ? "mm" : "m"));
        ExportOptions options;
        options.blender_method = parse_cycles_mapping(blender_method, "blender_method");
        if (blender_version) {
          if (*blender_version != 3 && *blender_version != 4)
            throw InvalidInput("blender_version", std::to_string(*blender_version), "3, 4 or None (auto)");
          options.blender_version = *blender_version;
        }
        std::string text;
        {
          const auto entries = export_entries(what, target, object_size, db);
          py::gil_scoped_release release;
          text = export_materials(target, entries, u, options);
        }
        if (output) write_file_atomically(*output, text);
        return text;
      },
      py::arg("materials"), py::arg("to"), py::arg("unit") = py::none(), py::arg("blender_method") = "fixed-radius",
      py::arg("blender_version") = py::none(), py::arg("object_size") = 10.0, py::arg("db") = "",
      py::arg("output") = py::none(),
      R"(Materials in a renderer's form, as `bssrdf materials export` writes them; returns the text.

materials: a name, Material or Medium, or a list of them; to: json, pbrt-v4, mitsuba3, blender,
unity-hdrp, unity-hdrp-editor, unreal, unreal-python; unit: the scene unit (default m; json: mm);
blender_method: fixed-radius, radius-remap or burley; blender_version: 3, 4 or None (the script
picks when run); object_size: mm; output: also write the text to this file (atomically).)");
  materials.def(
      "from_fit",
      [](const std::string& fit, const std::string& name, std::optional<double> eta, const std::string& source) {
        // A fit result object's JSON, a file holding it, or the JSON text itself.
        std::string text = fit, file = "fit";
        if (!fit.empty() && fit.front() != '{') {
          text = read_data_file(fit, "the fit result");
          file = fit;
        }
        MaterialDatabase db;
        db.add_text(materials_file_from_fit(text, file, name, eta, source), name + ".json");
        return db.all().front();
      },
      py::arg("fit"), py::arg("name"), py::arg("eta") = py::none(), py::arg("source") = "fit",
      "A fit result (FitResult.to_json(), or a file of `bssrdf fit ... -f json`) as a Material (`bssrdf "
      "materials import`).");

  py::class_<DerivedChannel>(m, "DerivedChannel", "What one channel's coefficients imply (lengths in mm).")
      .def_readonly("name", &DerivedChannel::name)
      .def_readonly("sigma_t", &DerivedChannel::sigma_t)
      .def_readonly("albedo", &DerivedChannel::albedo)
      .def_readonly("sigma_s_prime", &DerivedChannel::sigma_s_prime)
      .def_readonly("albedo_prime", &DerivedChannel::albedo_prime)
      .def_readonly("mfp", &DerivedChannel::mfp)
      .def_readonly("transport_mfp", &DerivedChannel::transport_mfp)
      .def_readonly("diffuse_mfp", &DerivedChannel::diffuse_mfp)
      .def_readonly("surface_albedo", &DerivedChannel::surface_albedo)
      .def_readonly("burley_d", &DerivedChannel::burley_d)
      .def_readonly("burley_error", &DerivedChannel::burley_error)
      .def_readonly("physical_model", &DerivedChannel::physical_model)
      .def_readonly("model_choice", &DerivedChannel::model_choice)
      .def_property_readonly("validity", [](const DerivedChannel& c) { return to_python(c.validity); });
  m.def(
      "derive",
      [](const py::object& medium, double object_size, const std::string& physical_model, const std::string& db) {
        const auto h = to_medium(medium, db);
        DerivationOptions options;
        options.object_size_mm = object_size;
        options.physical_model = physical_model;
        py::gil_scoped_release release;
        return derive_quantities(h.medium, options).channels;
      },
      py::arg("medium"), py::arg("object_size") = 10.0, py::arg("physical_model") = "", py::arg("db") = "",
      "Per channel: albedos, the four distance conventions (mm), the surface albedo and Burley's d fitted to the "
      "physical profile, and that profile's validity (`bssrdf materials show`).");

  py::class_<CyclesInputs>(m, "CyclesInputs",
                           "Principled BSDF inputs that make Cycles simulate a medium (lengths in the scene unit).")
      .def_property_readonly("method", [](const CyclesInputs& c) { return std::string(to_string(c.mapping)); })
      .def_readonly("albedo_color", &CyclesInputs::albedo_color, "Base Color (and 3.x Subsurface Color)")
      .def_readonly("radius", &CyclesInputs::radius, "Subsurface Radius per channel (scene unit)")
      .def_readonly("eta", &CyclesInputs::eta, "Subsurface IOR")
      .def_readonly("g", &CyclesInputs::g, "Subsurface Anisotropy")
      .def_readonly("notes", &CyclesInputs::notes, "where Cycles cannot represent the medium, one line each")
      .def_property_readonly("simulated_sigma_t", [](const CyclesInputs& c) { return c.simulated.sigma_t; })
      .def_property_readonly("simulated_alpha", [](const CyclesInputs& c) { return c.simulated.alpha; })
      .def_readonly("target_sigma_t", &CyclesInputs::target_sigma_t)
      .def_readonly("target_alpha", &CyclesInputs::target_alpha)
      .def(
          "blender_method",
          [](const CyclesInputs& c, int major) { return std::string(blender_method_identifier(c.mapping, major)); },
          py::arg("blender_major"), "Blender's enum identifier of the method in that major version (3 or 4).");
  m.def(
      "cycles_inputs",
      [](const py::object& medium, const std::string& method, const std::string& unit, double object_size,
         const std::string& db) {
        const auto h = to_medium(medium, db);
        const auto mapping = parse_cycles_mapping(method, "method");
        const auto u = parse_length_unit(unit);
        DerivationOptions options;
        options.object_size_mm = object_size;
        py::gil_scoped_release release;
        return cycles_inputs(h.medium, derive_quantities(h.medium, options), mapping, millimetres_per(u));
      },
      py::arg("medium"), py::arg("method") = "fixed-radius", py::arg("unit") = "m", py::arg("object_size") = 10.0,
      py::arg("db") = "",
      "The Principled BSDF inputs that make Cycles simulate the medium (what `materials export --to blender` "
      "writes): method fixed-radius, radius-remap or burley; unit: the scene unit.");
}

}  // namespace bssrdf::python
