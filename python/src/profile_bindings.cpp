// bssrdf.profile (what `bssrdf profile` prints, as arrays), bssrdf.Model (R(r) of one model, the
// fast path: one call for any number of radii), the model registry, validity and the model choice.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "bindings.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/lut/projected_profile.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_choice.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/model_selection.hpp"
#include "bssrdf/profile.hpp"
#include "bssrdf/profile_report.hpp"

namespace bssrdf::python {
namespace {

// A model by registry name, shared by every call that names it (the exact model's table loads once).
std::shared_ptr<const Model> shared_model(const std::string& name) {
  static std::map<std::string, std::shared_ptr<const Model>> cache;
  auto it = cache.find(name);
  if (it == cache.end()) it = cache.emplace(name, std::shared_ptr<const Model>(make_model(name))).first;
  return it->second;
}

// R(r) of every channel at n radii (in the medium's unit or `unit`): channels x n, 1/unit^2.
Array reflectance(const Model& model, const MediumHandle& h, const double* radius, std::size_t n,
                  const std::optional<std::string>& unit) {
  const double mm = millimetres_per(output_unit(unit, h));
  for (std::size_t i = 0; i < n; ++i)
    if (!(radius[i] >= 0 && std::isfinite(radius[i])))
      throw InvalidInput("r[" + std::to_string(i) + "]", format_number(radius[i]), ">= 0 and finite");
  const std::size_t channels = h.medium.channels();
  Array out({static_cast<py::ssize_t>(channels), static_cast<py::ssize_t>(n)});
  double* value = out.mutable_data();
  {
    // Other Python threads may run during long calls; a short one keeps the GIL (releasing costs a
    // good part of the 5 us per-call budget).
    std::optional<py::gil_scoped_release> release;
    if (n * channels > 256) release.emplace();
    for (std::size_t c = 0; c < channels; ++c) {
      const auto m = h.medium.reduced(c);
      for (std::size_t i = 0; i < n; ++i) value[c * n + i] = model.reflectance(m, radius[i] * mm) * mm * mm;
    }
  }
  return out;
}

Array reflectance(const Model& model, const MediumHandle& h, const Array& r, const std::optional<std::string>& unit) {
  if (r.ndim() > 1) throw InvalidInput("r: a number or a 1-D array of radii, not " + std::to_string(r.ndim()) + "-D");
  return reflectance(model, h, r.data(), static_cast<std::size_t>(r.size()), unit);
}

std::vector<double> per_channel(const MediumHandle& h, const std::function<double(const Reduced<double>&)>& f) {
  std::vector<double> out;
  for (std::size_t c = 0; c < h.medium.channels(); ++c) out.push_back(f(h.medium.reduced(c)));
  return out;
}

// The radii `bssrdf profile` takes: explicit, or `samples` from r_min to r_max (defaults from the medium).
std::vector<double> profile_radii_mm(const py::object& r, const Medium& medium, const Model& model, double mm,
                                     int samples, std::optional<double> r_min, std::optional<double> r_max,
                                     const std::string& spacing) {
  if (!r.is_none()) {
    std::vector<double> radii = to_vector(r, "r");
    if (radii.empty()) throw InvalidInput("r: give at least one radius");
    if (radii.size() == 1) {
      if (!(radii[0] >= 0 && std::isfinite(radii[0])))
        throw InvalidInput("r", format_number(radii[0]), ">= 0 and finite");
    } else {
      SampledProfile check;
      check.radius = radii;
      check.value.assign(radii.size(), 0.0);
      check.validate();
    }
    for (double& x : radii) x *= mm;
    return radii;
  }
  if (spacing != "log" && spacing != "linear") throw InvalidInput("spacing", "'" + spacing + "'", "log or linear");
  if (samples < 2 || samples > 1000000) throw InvalidInput("samples", std::to_string(samples), "2 to 1000000");
  const auto n = static_cast<std::size_t>(samples);
  const auto defaults = default_radii_mm(medium, model, n);
  double lo = r_min ? *r_min * mm : defaults.front();
  const double hi = r_max ? *r_max * mm : defaults.back();
  if (spacing == "linear" && !r_min) lo = 0;
  if (spacing == "log" && !(lo > 0)) throw InvalidInput("r_min", format_number(lo / mm), "> 0 with log spacing");
  if (!(hi > lo)) throw InvalidInput("r_max", format_number(hi / mm), "> r_min = " + format_number(lo / mm));
  return spacing == "log" ? log_spaced(lo, hi, n) : linear_spaced(lo, hi, n);
}

// A ProfileReport with numpy views for scripts.
struct Profile {
  ProfileReport report;
};

}  // namespace

void bind_profile(py::module_& m) {
  py::class_<Model, std::shared_ptr<Model>>(m, "Model", R"(One profile model of the registry, evaluated directly.

Model(name): e.g. Model("exact"), Model("better-dipole"), Model("quantized+ss") (bssrdf.models() lists them).
R(medium, r) -> channels x radii array: R(r) per unit entered flux, 1/unit^2, radii in the medium's unit.)")
      .def(py::init([](const std::string& name) { return std::const_pointer_cast<Model>(shared_model(name)); }),
           py::arg("name"))
      .def_property_readonly("name", &Model::name)
      .def_property_readonly("description", &Model::description, "one line with the citation")
      .def_property_readonly("includes_single_scattering", &Model::includes_single_scattering)
      // One radius as a Python number: no array to convert (the per-call overhead python/bench measures).
      .def(
          "R",
          [](const Model& model, const MediumHandle& medium, double r, const std::optional<std::string>& unit) {
            return reflectance(model, medium, &r, 1, unit);
          },
          py::arg("medium"), py::arg("r"), py::arg("unit") = py::none())
      .def(
          "R",
          [](const Model& model, const MediumHandle& medium, const Array& r, const std::optional<std::string>& unit) {
            return reflectance(model, medium, r, unit);
          },
          py::arg("medium"), py::arg("r"), py::arg("unit") = py::none(),
          "R(r) of every channel at radii r (a number or a 1-D array, in the medium's unit or `unit`): a channels x "
          "radii array, 1/unit^2, per unit entered flux.")
      .def(
          "R",
          [](const Model& model, const py::object& medium, const Array& r, const std::optional<std::string>& unit) {
            return reflectance(model, to_medium(medium), r, unit);
          },
          py::arg("medium"), py::arg("r"), py::arg("unit") = py::none())
      .def(
          "total",
          [](const Model& model, const py::object& medium) {
            const auto h = to_medium(medium);
            return to_array(per_channel(h, [&](const auto& m) { return model.total_reflectance(m); }));
          },
          py::arg("medium"), "Total diffuse reflectance per channel: the integral of 2 pi r R(r) dr.")
      .def(
          "radius_for_fraction",
          [](const Model& model, const py::object& medium, double fraction, const std::optional<std::string>& unit) {
            const auto h = to_medium(medium);
            if (!(fraction > 0 && fraction < 1))
              throw InvalidInput("fraction", format_number(fraction), "0 < fraction < 1");
            const double mm = millimetres_per(output_unit(unit, h));
            return to_array(per_channel(h, [&](const auto& m) { return model.radius_for_fraction(m, fraction) / mm; }));
          },
          py::arg("medium"), py::arg("fraction") = 0.99, py::arg("unit") = py::none(),
          "The radius holding `fraction` of the total reflectance, per channel (medium's unit or `unit`).")
      .def(
          "validity",
          [](const Model& model, const py::object& medium) {
            const auto h = to_medium(medium);
            std::vector<py::list> out;
            for (std::size_t c = 0; c < h.medium.channels(); ++c)
              out.push_back(to_python(model.validity(h.medium.reduced(c))));
            return out;
          },
          py::arg("medium"), "Per channel, the model's validity notes (empty: nothing to report).")
      .def(
          "half_plane",
          [](const Model& model, const py::object& medium, const py::object& x,
             const std::optional<std::string>& unit) {
            const auto h = to_medium(medium);
            const double mm = millimetres_per(output_unit(unit, h));
            const auto xs = to_vector(x, "x");
            for (std::size_t i = 0; i < xs.size(); ++i)
              if (!std::isfinite(xs[i]))
                throw InvalidInput("x[" + std::to_string(i) + "]", format_number(xs[i]), "finite");
            std::vector<std::vector<double>> rows;
            for (std::size_t c = 0; c < h.medium.channels(); ++c) {
              const ProjectedProfile p(model, h.medium.reduced(c));
              rows.emplace_back();
              for (double v : xs) rows.back().push_back(p.half_plane(v * mm));
            }
            return to_array(rows);
          },
          py::arg("medium"), py::arg("x"), py::arg("unit") = py::none(),
          "The exitance at signed distance x from the edge of a lit half-plane X > x (a shadow edge), per unit "
          "incident flux density: channels x len(x); x in the medium's unit or `unit`. half_plane(-inf) is the total.")
      .def("__repr__", [](const Model& model) { return "<Model " + model.name() + ">"; });

  // The C++ side of python/bench/bench_module.py: the same evaluations as Model.R, in a C++ loop into a
  // preallocated buffer, timed in C++ (seconds per call, the median of `repeats`).
  m.def(
      "_bench_reflectance",
      [](const Model& model, const MediumHandle& h, const Array& r, int repeats) {
        const auto n = static_cast<std::size_t>(r.size());
        const double* radius = r.data();
        const double mm = millimetres_per(h.unit);
        std::vector<double> out(h.medium.channels() * n);
        std::vector<double> seconds;
        py::gil_scoped_release release;
        for (int k = 0; k < repeats; ++k) {
          const auto start = std::chrono::steady_clock::now();
          for (std::size_t c = 0; c < h.medium.channels(); ++c) {
            const auto m = h.medium.reduced(c);
            for (std::size_t i = 0; i < n; ++i) out[c * n + i] = model.reflectance(m, radius[i] * mm) * mm * mm;
          }
          seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        }
        std::sort(seconds.begin(), seconds.end());
        return seconds[seconds.size() / 2];
      },
      py::arg("model"), py::arg("medium"), py::arg("r"), py::arg("repeats") = 5);

  py::class_<Profile>(m, "Profile", R"(R(r) of every channel under one model, as `bssrdf profile` computes it.

np.asarray(p) (or p.values) is the channels x radii array, 1/unit^2; p.radius the radii in p.unit.)")
      .def_property_readonly("model", [](const Profile& p) { return p.report.model; })
      .def_property_readonly("model_description", [](const Profile& p) { return p.report.model_description; })
      .def_property_readonly(
          "model_choice", [](const Profile& p) { return p.report.model_choice; },
          "why this model (auto's choice, or why the default is not exact); empty otherwise")
      .def_property_readonly("includes_single_scattering",
                             [](const Profile& p) { return p.report.includes_single_scattering; })
      .def_property_readonly("unit", [](const Profile& p) { return std::string(symbol(p.report.unit)); })
      .def_property_readonly("channels",
                             [](const Profile& p) {
                               std::vector<std::string> names;
                               for (const auto& ch : p.report.channels) names.push_back(ch.name);
                               return names;
                             })
      .def_property_readonly("radius",
                             [](const Profile& p) { return to_array(p.report.channels.front().profile.radius); })
      .def_property_readonly(
          "values",
          [](const Profile& p) {
            std::vector<std::vector<double>> rows;
            for (const auto& ch : p.report.channels) rows.push_back(ch.profile.value);
            return to_array(rows);
          },
          "channels x radii, 1/unit^2")
      .def(
          "__array__",
          [](const Profile& p, const py::object&) {
            std::vector<std::vector<double>> rows;
            for (const auto& ch : p.report.channels) rows.push_back(ch.profile.value);
            return to_array(rows);
          },
          py::arg("dtype") = py::none())
      .def(
          "total",
          [](const Profile& p) {
            std::vector<double> v;
            for (const auto& ch : p.report.channels) v.push_back(ch.total_reflectance);
            return to_array(v);
          },
          "Total diffuse reflectance per channel (the model's, to infinity)")
      .def_property_readonly(
          "radius_99",
          [](const Profile& p) {
            std::vector<double> v;
            for (const auto& ch : p.report.channels) v.push_back(ch.radius_99);
            return to_array(v);
          },
          "radius holding 99 % of the total, per channel (unit)")
      .def_property_readonly(
          "validity",
          [](const Profile& p) {
            std::vector<py::list> out;
            for (const auto& ch : p.report.channels) out.push_back(to_python(ch.validity));
            return out;
          },
          "per channel, the model's validity notes")
      .def(
          "to_json", [](const Profile& p) { return to_json(p.report); }, "The JSON `bssrdf profile -f json` prints.")
      .def(
          "to_csv", [](const Profile& p) { return to_csv(p.report); }, "The CSV `bssrdf profile -f csv` prints.")
      .def("__str__", [](const Profile& p) { return to_table(p.report); })
      .def("__repr__", [](const Profile& p) {
        return "<Profile " + p.report.model + ": " + std::to_string(p.report.channels.size()) + " channels x " +
               std::to_string(p.report.channels.front().profile.size()) + " radii>";
      });

  m.def(
      "profile",
      [](const py::object& medium, const py::object& r, const std::string& model,
         const std::optional<std::string>& unit, int samples, std::optional<double> r_min, std::optional<double> r_max,
         const std::string& spacing, std::optional<double> accuracy, bool single_scattering,
         std::optional<double> surface_albedo, const std::string& db) {
        const auto h = to_medium(medium, db);
        const auto u = output_unit(unit, h);
        const auto chosen = select_model(model, accuracy, h.medium);
        if (model == "auto" && single_scattering)
          throw InvalidInput("single_scattering: not with model auto (the choice includes NAME+ss models)");
        if (model.empty() && single_scattering && model_entry(chosen.name).includes_single_scattering)
          throw InvalidInput("single_scattering: the default model here, " + chosen.name +
                             ", includes single scattering already; give model=NAME for one that omits it");
        std::shared_ptr<const Model> forward = shared_model(chosen.name + (single_scattering ? "+ss" : ""));
        if (surface_albedo) {
          const double A = *surface_albedo;
          if (!(A > 0 && A < 1)) throw InvalidInput("surface_albedo", format_number(A), "0 < A < 1");
          const auto& entry = model_entry(forward->name());
          if (!entry.with_surface_albedo)
            throw InvalidInput("surface_albedo: only the burley models take a surface albedo, not " + forward->name());
          forward = entry.with_surface_albedo(A);
        }
        const double mm = millimetres_per(u);
        const auto radii = profile_radii_mm(r, h.medium, *forward, mm, samples, r_min, r_max, spacing);
        Profile out;
        {
          py::gil_scoped_release release;
          out.report = compute_profile_report(h.medium, *forward, radii, u);
        }
        out.report.material = h.material;
        out.report.model_choice = chosen.note;
        return out;
      },
      py::arg("medium"), py::arg("r") = py::none(), py::arg("model") = "", py::kw_only(), py::arg("unit") = py::none(),
      py::arg("samples") = 64, py::arg("r_min") = py::none(), py::arg("r_max") = py::none(), py::arg("spacing") = "log",
      py::arg("accuracy") = py::none(), py::arg("single_scattering") = false, py::arg("surface_albedo") = py::none(),
      py::arg("db") = "",
      R"(R(r) of every channel of a medium under one model: `bssrdf profile`.

medium: a Medium, a Material or a material's name; r: radii (medium's unit or `unit`), default
`samples` radii from 1e-3 of the smallest transport mfp to the largest 99.9 %-energy radius;
model: a registry name, "" (the registry's default: exact inside its domain) or "auto" (the
cheapest measured within `accuracy`, default 0.1). Returns a Profile.)");

  py::class_<ModelEntry>(m, "ModelInfo",
                         "A row of the model registry: what a model includes, costs and where it holds.")
      .def_readonly("name", &ModelEntry::name)
      .def_property_readonly("description", [](const ModelEntry& e) { return e.make()->description(); })
      .def_readonly("includes_single_scattering", &ModelEntry::includes_single_scattering)
      .def_readonly("cost_ns", &ModelEntry::cost_ns, "one R(r) evaluation, ns (bench_models median)")
      .def_readonly("closed_form", &ModelEntry::closed_form)
      .def_readonly("auto_candidate", &ModelEntry::auto_candidate, "served by model='auto'")
      .def_readonly("listed", &ModelEntry::listed, "shown by `bssrdf models` (NAME+ss rows are not)")
      .def_property_readonly("domain", &measured_domain, "where it holds, as `bssrdf models` says it")
      .def_property_readonly(
          "bands",
          [](const ModelEntry& e) -> py::object {
            if (!e.limits) return py::none();
            const auto rows = [](const std::vector<AccuracyBand>& bands) {
              py::list out;
              for (const auto& b : bands) out.append(py::make_tuple(b.min_albedo_prime, b.worst_error));
              return out;
            };
            py::dict d;
            d["isotropic"] = rows(e.limits->isotropic_bands);
            d["forward"] = rows(e.limits->forward_bands);
            return d;
          },
          "measured total error against adding-doubling: {'isotropic' (g 0), 'forward' (g 0.9): [(alpha'_min, worst "
          "error), ...]}, or None")
      .def_property_readonly(
          "reference_accuracy",
          [](const ModelEntry& e) -> py::object {
            if (!e.reference_accuracy) return py::none();
            py::dict d;
            d["total"] = e.reference_accuracy->total;
            d["profile"] = e.reference_accuracy->profile;
            return d;
          },
          "a reference model's band against fresh Monte Carlo (total, profile L2), or None")
      .def("__repr__", [](const ModelEntry& e) { return "<ModelInfo " + e.name + ">"; });
  m.def(
      "models",
      [](bool all) {
        std::vector<const ModelEntry*> out;
        for (const auto& e : model_registry())
          if (all || e.listed) out.push_back(&e);
        return out;
      },
      py::arg("all") = false, py::return_value_policy::reference,
      "The model registry in `bssrdf models` order (all=True: the NAME+ss rows too).");

  py::class_<ModelErrorEstimate>(m, "ModelErrorEstimate", "A model's measured error at a medium (worst channel).")
      .def_readonly("model", &ModelErrorEstimate::model)
      .def_readonly("cost_ns", &ModelErrorEstimate::cost_ns)
      .def_readonly("total_error", &ModelErrorEstimate::total_error)
      .def_readonly("profile_error", &ModelErrorEstimate::profile_error)
      .def_readonly("near_error", &ModelErrorEstimate::near_error)
      .def_readonly("far_error", &ModelErrorEstimate::far_error)
      .def_readonly("source", &ModelErrorEstimate::source, "exact, table or exact+table")
      .def_readonly("invalid", &ModelErrorEstimate::invalid)
      .def("error", &ModelErrorEstimate::error)
      .def("__repr__", [](const ModelErrorEstimate& e) {
        return "<ModelErrorEstimate " + e.model + ": total " + short_number(e.total_error) + ", profile " +
               short_number(e.profile_error) + ">";
      });
  m.def(
      "model_errors",
      [](const py::object& medium) {
        const auto h = to_medium(medium);
        py::gil_scoped_release release;
        return estimate_model_errors(h.medium);
      },
      py::arg("medium"),
      "Every candidate's measured error at this medium, cheapest first (`bssrdf models --material`).");
  py::class_<SelectedModel>(m, "ModelSelection", "A chosen model and the line saying why.")
      .def_readonly("name", &SelectedModel::name)
      .def_readonly("note", &SelectedModel::note)
      .def("__repr__", [](const SelectedModel& s) { return "<ModelSelection " + s.name + ">"; });
  m.def(
      "select_model",
      [](const py::object& medium, const std::string& model, std::optional<double> accuracy) {
        const auto h = to_medium(medium);
        py::gil_scoped_release release;
        return select_model(model, accuracy, h.medium);
      },
      py::arg("medium"), py::arg("model") = "", py::arg("accuracy") = py::none(),
      "The model a request means: '' the registry's default, 'auto' the cheapest within accuracy, else the name; "
      "with the CLI's explanation in .note.");
  m.def(
      "validity",
      [](const py::object& medium, const std::string& model) {
        const auto h = to_medium(medium);
        const auto forward = shared_model(select_model(model, std::nullopt, h.medium).name);
        std::vector<py::list> out;
        for (std::size_t c = 0; c < h.medium.channels(); ++c)
          out.push_back(to_python(forward->validity(h.medium.reduced(c))));
        return out;
      },
      py::arg("medium"), py::arg("model") = "",
      "Per channel, where the model (default: the registry's) does not hold for this medium.");
}

}  // namespace bssrdf::python
