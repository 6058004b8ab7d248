// Fits (`bssrdf fit profile|albedo|slab|gaussians|burley`, `fit slab --rxt`), tables (every `bssrdf lut`
// kind) and `advise`. The lut kinds go through the command line's own option mapping (src/cli/lut_kinds.cpp)
// so that a keyword here and a flag there can never build different tables; its messages name flags,
// which errors here rename to the keyword (--table-tolerance -> table_tolerance).
#include <cmath>
#include <regex>

#include "bindings.hpp"
#include "bssrdf/advise/advise.hpp"
#include "bssrdf/advise/auto_reference.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/fit/fit_report.hpp"
#include "bssrdf/fit/inverse_fits.hpp"
#include "bssrdf/fit/profile_fit.hpp"
#include "bssrdf/fit/rxt_fit.hpp"
#include "bssrdf/image/reference_profile.hpp"
#include "bssrdf/io/atomic_file.hpp"
#include "bssrdf/io/exr_table.hpp"
#include "bssrdf/io/profile_csv.hpp"
#include "bssrdf/io/rxt.hpp"
#include "bssrdf/lut/table_kinds.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/model_selection.hpp"
#include "bssrdf/profile_report.hpp"
#include "cli/lut_kinds.hpp"
#include "cli/rxt_output.hpp"

namespace bssrdf::python {
namespace {

// "--table-tolerance = 0: ..." -> "table_tolerance = 0: ...".
[[noreturn]] void rethrow_with_keywords(const InvalidInput& e) {
  static const std::regex flag("--([a-z][a-z-]*)");
  std::string message, text = e.what();
  std::smatch match;
  while (std::regex_search(text, match, flag)) {
    std::string name = match[1];
    std::replace(name.begin(), name.end(), '-', '_');
    message += match.prefix().str() + name;
    text = match.suffix();
  }
  throw InvalidInput(message + text);
}

std::string number_text(const std::optional<double>& v) { return v ? format_number(*v) : ""; }

std::vector<double> per_channel(const py::object& values, std::size_t n, const std::string& field, double fallback) {
  if (values.is_none()) return std::vector<double>(n, fallback);
  auto v = to_vector(values, field);
  if (v.size() == 1 && n > 1) v.assign(n, v[0]);
  if (v.size() != n)
    throw InvalidInput(field + ": " + std::to_string(v.size()) + " values given for " + std::to_string(n) +
                       " channels");
  return v;
}

std::vector<std::string> names_for(const std::optional<std::vector<std::string>>& channels, std::size_t n) {
  auto names = channels ? *channels : default_channel_names(n);
  if (names.size() != n)
    throw InvalidInput("channels: " + std::to_string(names.size()) + " names for " + std::to_string(n) + " channels");
  return names;
}

// A radial profile to fit Gaussians or Burley's d to: a CSV file, or a medium's profile under a model.
std::pair<std::vector<NamedProfile>, std::string> profile_source(const py::object& source, const std::string& model,
                                                                 int samples, LengthUnit& unit) {
  std::vector<NamedProfile> out;
  if (py::isinstance<py::str>(source) && std::string(py::str(source)).find('.') != std::string::npos &&
      std::string(py::str(source)).ends_with(".csv")) {
    const std::string file = source.cast<std::string>();
    const auto measured = read_profile_csv(file);
    unit = measured.unit;
    return {named_profiles_in_own_unit(measured), file};
  }
  const auto h = to_medium(source);
  unit = h.unit;
  const auto chosen = select_model(model, std::nullopt, h.medium);
  const auto m = make_model(chosen.name);
  if (samples < 8 || samples > 100000) throw InvalidInput("samples", std::to_string(samples), "8 to 100000");
  const auto report = compute_profile_report(h.medium, *m, default_radii_mm(h.medium, *m, samples), unit);
  for (const auto& ch : report.channels) out.push_back({ch.name, ch.profile});
  return {out, chosen.name + " profile of " + (h.material ? h.material->name : std::string("the given medium")) +
                   (chosen.note.empty() ? "" : " (" + chosen.note + ")")};
}

struct Table {
  BuiltTable built;
};

std::string encode(const BuiltTable& built, const std::string& format, bool half) {
  const auto other = built.other_formats.find(format);
  if (other != built.other_formats.end()) return other->second();
  if (format == "exr") return encode_exr(built.table, half ? ExrPixelType::half : ExrPixelType::float32);
  if (format == "json") return to_json(built.table);
  if (format == "csv") return to_csv(built.table);
  throw InvalidInput("format", "'" + format + "'", "exr, json, csv, or glsl/hlsl for kind separable");
}

py::object attribute_value(const AttributeValue& v) {
  return std::visit([](const auto& x) { return py::cast(x); }, v);
}

struct AdviceResult {
  Advice advice;
  std::string name;
};

}  // namespace

void bind_tables(py::module_& m) {
  // ---- fits ----
  py::class_<FitParameter>(m, "FitParameter", "A fitted value with its 1-sigma standard error.")
      .def_readonly("name", &FitParameter::name)
      .def_readonly("channel", &FitParameter::channel)
      .def_readonly("value", &FitParameter::value)
      .def_readonly("standard_error", &FitParameter::standard_error)
      .def_readonly("unit", &FitParameter::unit)
      .def("__repr__", [](const FitParameter& p) {
        return "<FitParameter " + p.name + (p.channel.empty() ? "" : "[" + p.channel + "]") + " = " +
               short_number(p.value) + " +- " + short_number(p.standard_error) + " " + p.unit + ">";
      });
  py::class_<FitReport>(m, "FitResult",
                        R"(What every fit returns: parameters with 1-sigma errors, residuals, the report.

r["sigma_a"] -> array over channels of the values; r.stderr("sigma_a") -> their standard errors.)")
      .def_readonly("kind", &FitReport::kind)
      .def_readonly("model", &FitReport::model)
      .def_readonly("model_choice", &FitReport::model_choice)
      .def_readonly("parameters", &FitReport::parameters)
      .def_readonly("converged", &FitReport::converged)
      .def_readonly("termination", &FitReport::termination)
      .def_readonly("iterations", &FitReport::iterations)
      .def_readonly("residual_rms", &FitReport::residual_rms)
      .def_readonly("relative_rms", &FitReport::relative_rms)
      .def_readonly("warnings", &FitReport::warnings)
      .def_readonly("seconds", &FitReport::seconds)
      .def("__getitem__",
           [](const FitReport& r, const std::string& name) {
             std::vector<double> v;
             for (const auto& p : r.parameters)
               if (p.name == name) v.push_back(p.value);
             if (v.empty()) throw py::key_error(name);
             return to_array(v);
           })
      .def(
          "stderr",
          [](const FitReport& r, const std::string& name) {
            std::vector<double> v;
            for (const auto& p : r.parameters)
              if (p.name == name) v.push_back(p.standard_error);
            if (v.empty()) throw py::key_error(name);
            return to_array(v);
          },
          py::arg("name"))
      .def("report", &FitReport::full_report, "The full report for people (Ceres' FullReport style).")
      .def("to_json", &FitReport::to_json, "The JSON `bssrdf fit ... -f json` prints.")
      .def("__str__", &FitReport::full_report);

  auto fit = m.def_submodule("fit", "Fits: profile, albedo, slab, rxt, gaussians, burley (`bssrdf fit`).");
  fit.def(
      "profile",
      [](const std::string& file, const std::string& model, double eta, bool fit_eta, bool fit_scale,
         const py::object& g, const std::string& loss, double loss_scale, const std::optional<std::string>& unit) {
        ProfileFitOptions options;
        options.model = model;
        options.eta = eta;
        options.fit_eta = fit_eta;
        options.fit_scale = fit_scale;
        if (!g.is_none()) options.g = to_vector(g, "g");
        options.loss = loss;
        options.loss_scale = loss_scale;
        const auto data = read_profile_csv(file, unit ? std::optional(parse_length_unit(*unit)) : std::nullopt);
        py::gil_scoped_release release;
        return fit_profile(data, options);
      },
      py::arg("file"), py::kw_only(), py::arg("model") = "", py::arg("eta") = 1.3, py::arg("fit_eta") = false,
      py::arg("fit_scale") = false, py::arg("g") = py::none(), py::arg("loss") = "none", py::arg("loss_scale") = 1.0,
      py::arg("unit") = py::none(),
      "sigma_a and sigma_s' per channel fitted to a measured radial profile (CSV: radius, one column per channel, "
      "optional <channel>_stderr): `bssrdf fit profile`.");
  fit.def(
      "albedo",
      [](const py::object& albedo, const py::object& distance, const std::string& convention, const std::string& unit,
         const std::string& model, double eta, const py::object& g,
         const std::optional<std::vector<std::string>>& channels) {
        const auto A = to_vector(albedo, "albedo");
        const auto n = A.size();
        const auto d = per_channel(distance, n, "distance", 0);
        const auto gs = per_channel(g, n, "g", 0);
        const auto names = names_for(channels, n);
        std::vector<ChannelInput> inputs;
        for (std::size_t c = 0; c < n; ++c) {
          if (!(A[c] >= 0 && A[c] <= 1)) throw InvalidInput("albedo[" + names[c] + "]", format_number(A[c]), "[0, 1]");
          if (!(gs[c] > -1 && gs[c] < 1)) throw InvalidInput("g[" + names[c] + "]", format_number(gs[c]), "-1 < g < 1");
          inputs.push_back({names[c], A[c], d[c], gs[c]});
        }
        const auto conv = parse_distance_convention(convention);
        const auto u = parse_length_unit(unit);
        py::gil_scoped_release release;
        return fit_albedo(inputs, conv, u, model, eta);
      },
      py::arg("albedo"), py::arg("distance"), py::kw_only(), py::arg("convention") = "mfp", py::arg("unit") = "mm",
      py::arg("model") = "", py::arg("eta") = 1.3, py::arg("g") = py::none(), py::arg("channels") = py::none(),
      "Surface albedo + one distance per channel -> sigma_a, sigma_s' (exact inversion): `bssrdf fit albedo`. "
      "convention: mfp, transport-mfp or dmfp.");
  fit.def(
      "slab",
      [](const py::object& reflectance, const py::object& transmittance, double thickness, const py::object& r_stderr,
         const py::object& t_stderr, const std::string& unit, double eta, const py::object& g,
         const py::object& unscattered, const py::object& u_stderr, std::optional<std::pair<double, double>> slides,
         const std::string& model, const std::optional<std::vector<std::string>>& channels) {
        const auto R = to_vector(reflectance, "reflectance");
        const auto n = R.size();
        const auto T = per_channel(transmittance, n, "transmittance", 0);
        const auto rs = per_channel(r_stderr, n, "reflectance_stderr", 0.002);
        const auto ts = per_channel(t_stderr, n, "transmittance_stderr", 0.002);
        const auto gs = per_channel(g, n, "g", 0);
        const auto U = per_channel(unscattered, n, "unscattered", -1);
        const auto us = per_channel(u_stderr, n, "unscattered_stderr", 0.002);
        const auto names = names_for(channels, n);
        for (std::size_t c = 0; c < n; ++c)
          if (!unscattered.is_none() && !(U[c] >= 0 && U[c] <= 1))
            throw InvalidInput("unscattered[" + names[c] + "]", format_number(U[c]), "[0, 1]");
        std::vector<SlabMeasurement> data;
        for (std::size_t c = 0; c < n; ++c) data.push_back({names[c], R[c], T[c], rs[c], ts[c], gs[c], U[c], us[c]});
        SlabFitOptions options;
        options.model = model;
        if (slides) std::tie(options.slide_n, options.slide_thickness) = *slides;
        const auto u = parse_length_unit(unit);
        py::gil_scoped_release release;
        return fit_slab(data, thickness, u, eta, options);
      },
      py::arg("reflectance"), py::arg("transmittance"), py::kw_only(), py::arg("thickness"),
      py::arg("reflectance_stderr") = py::none(), py::arg("transmittance_stderr") = py::none(), py::arg("unit") = "mm",
      py::arg("eta") = 1.4, py::arg("g") = py::none(), py::arg("unscattered") = py::none(),
      py::arg("unscattered_stderr") = py::none(), py::arg("slides") = py::none(), py::arg("model") = "adding-doubling",
      py::arg("channels") = py::none(),
      "Integrating-sphere R and T (and unscattered U) of a slab -> sigma_a, sigma_s' (and g): `bssrdf fit slab`.");

  py::class_<RxtFit>(m, "RxtFit",
                     "Inverse adding-doubling of a .rxt file: per row mu_a, mu_s', g with 1-sigma errors (1/mm).")
      .def_property_readonly("wavelength",
                             [](const RxtFit& f) {
                               std::vector<double> v;
                               for (const auto& r : f.rows) v.push_back(r.row.wavelength);
                               return to_array(v);
                             })
      .def_property_readonly("mu_a",
                             [](const RxtFit& f) {
                               std::vector<double> v;
                               for (const auto& r : f.rows) v.push_back(r.mu_a);
                               return to_array(v);
                             })
      .def_property_readonly("mu_a_stderr",
                             [](const RxtFit& f) {
                               std::vector<double> v;
                               for (const auto& r : f.rows) v.push_back(r.mu_a_stderr);
                               return to_array(v);
                             })
      .def_property_readonly("mu_s_prime",
                             [](const RxtFit& f) {
                               std::vector<double> v;
                               for (const auto& r : f.rows) v.push_back(r.mu_s_prime);
                               return to_array(v);
                             })
      .def_property_readonly("mu_s_prime_stderr",
                             [](const RxtFit& f) {
                               std::vector<double> v;
                               for (const auto& r : f.rows) v.push_back(r.mu_s_prime_stderr);
                               return to_array(v);
                             })
      .def_property_readonly("g",
                             [](const RxtFit& f) {
                               std::vector<double> v;
                               for (const auto& r : f.rows) v.push_back(r.g);
                               return to_array(v);
                             })
      .def_property_readonly("status",
                             [](const RxtFit& f) {
                               std::vector<std::string> v;
                               for (const auto& r : f.rows) v.push_back(r.status);
                               return v;
                             })
      .def_property_readonly("converged",
                             [](const RxtFit& f) {
                               std::vector<bool> v;
                               for (const auto& r : f.rows) v.push_back(r.converged);
                               return v;
                             })
      .def(
          "to_json", [](const RxtFit& f) { return cli::rxt_fit_json(f); }, "The JSON `bssrdf fit slab --rxt` prints.")
      .def("to_csv", [](const RxtFit& f) { return cli::rxt_fit_csv(f); })
      .def("__str__", [](const RxtFit& f) { return cli::rxt_fit_table(f); });
  fit.def(
      "rxt",
      [](const std::string& file, double g, double r_stderr, double t_stderr, double u_stderr, bool lost_light,
         std::int64_t lost_light_photons) {
        RxtFitOptions options;
        options.g = g;
        options.reflectance_stderr = r_stderr;
        options.transmittance_stderr = t_stderr;
        options.unscattered_stderr = u_stderr;
        options.lost_light = lost_light;
        options.lost_light_photons = checked_count(lost_light_photons, "lost_light_photons", 1, 10'000'000'000);
        const auto data = read_rxt(file);
        py::gil_scoped_release release;
        return fit_rxt(data, options);
      },
      py::arg("file"), py::kw_only(), py::arg("g") = NAN, py::arg("reflectance_stderr") = 0.002,
      py::arg("transmittance_stderr") = 0.002, py::arg("unscattered_stderr") = 0.002, py::arg("lost_light") = false,
      py::arg("lost_light_photons") = 100000,
      "Every row of an integrating-sphere file of Prahl's iad (.rxt): `bssrdf fit slab --rxt FILE`.");
  fit.def(
      "gaussians",
      [](const py::object& source, int count, const std::string& model, int samples) {
        if (count < 1 || count > 32) throw InvalidInput("count", std::to_string(count), "1 to 32");
        LengthUnit unit = LengthUnit::millimetre;
        const auto [profiles, label] = profile_source(source, model, samples, unit);
        py::gil_scoped_release release;
        return fit_gaussians(profiles, count, unit, label);
      },
      py::arg("source"), py::arg("count") = 6, py::kw_only(), py::arg("model") = "", py::arg("samples") = 128,
      "N shared-variance Gaussians fitted to a profile (a CSV file, or a medium's profile under `model`).");
  fit.def(
      "burley",
      [](const py::object& source, const std::string& model, int samples) {
        LengthUnit unit = LengthUnit::millimetre;
        const auto [profiles, label] = profile_source(source, model, samples, unit);
        py::gil_scoped_release release;
        return fit_burley(profiles, unit, label);
      },
      py::arg("source"), py::kw_only(), py::arg("model") = "", py::arg("samples") = 128,
      "Burley's d per channel fitted to a profile (a CSV file, or a medium's profile under `model`).");

  // ---- tables ----
  py::class_<Table>(m, "Table", R"(A lookup table (`bssrdf lut`): named channels on a width x height grid plus metadata.

t["R"] -> the channel as a height x width array (1-D tables: width); t.attributes: what every number is.)")
      .def_property_readonly("kind", [](const Table& t) { return t.built.table.kind; })
      .def_property_readonly("width", [](const Table& t) { return t.built.table.width; })
      .def_property_readonly("height", [](const Table& t) { return t.built.table.height; })
      .def_property_readonly("channels",
                             [](const Table& t) {
                               std::vector<std::string> names;
                               for (const auto& c : t.built.table.channels) names.push_back(c.name);
                               return names;
                             })
      .def("__getitem__",
           [](const Table& t, const std::string& name) {
             const auto& c = t.built.table.channel(name);
             Array out = to_array(c.values);
             if (t.built.table.height > 1)
               out.resize(
                   {static_cast<py::ssize_t>(t.built.table.height), static_cast<py::ssize_t>(t.built.table.width)});
             return out;
           })
      .def("description",
           [](const Table& t, const std::string& name) { return t.built.table.channel(name).description; })
      .def_property_readonly("attributes",
                             [](const Table& t) {
                               py::dict d;
                               for (const auto& a : t.built.table.attributes)
                                 d[py::str(a.name)] = attribute_value(a.value);
                               return d;
                             })
      .def_property_readonly("axes",
                             [](const Table& t) {
                               py::dict d;
                               for (const auto* axis : {&t.built.table.x_axis, &t.built.table.y_axis})
                                 if (!axis->values.empty()) d[py::str(axis->name)] = to_array(axis->values);
                               return d;
                             })
      .def_property_readonly(
          "summary", [](const Table& t) { return t.built.summary; }, "the lines `bssrdf lut` prints")
      .def("to_json", [](const Table& t) { return to_json(t.built.table); })
      .def("to_csv", [](const Table& t) { return to_csv(t.built.table); })
      .def(
          "encode",
          [](const Table& t, const std::string& format, bool half) { return py::bytes(encode(t.built, format, half)); },
          py::arg("format"), py::arg("half") = false,
          "The file's bytes: exr, json, csv (glsl, hlsl: separable kernels).")
      .def(
          "write",
          [](const Table& t, const std::string& path, const std::optional<std::string>& format, bool half) {
            std::string f = format.value_or("");
            if (f.empty()) {
              const auto ext = std::filesystem::path(path).extension().string();
              if (ext.size() > 1) f = ext.substr(1);
            }
            write_file_atomically(path, encode(t.built, f, half));
          },
          py::arg("path"), py::arg("format") = py::none(), py::arg("half") = false,
          "Write the table atomically, in the format of the file's extension (.exr, .json, .csv, .glsl, .hlsl).")
      .def("__repr__", [](const Table& t) {
        return "<Table " + t.built.table.kind + " " + std::to_string(t.built.table.width) + " x " +
               std::to_string(t.built.table.height) + ">";
      });

  m.def(
      "lut",
      [](const py::object& medium, const std::string& kind, const std::string& model,
         const std::optional<double> accuracy, const std::optional<std::string>& unit,
         const std::optional<double> tolerance, const std::optional<double> energy,
         const std::optional<std::string>& interpolation, const std::string& layout,
         const std::optional<std::string>& size, const std::optional<double> table_tolerance,
         const py::object& thickness, const std::optional<double> d_min, const std::optional<double> d_max, int samples,
         bool reference, bool reference_everywhere, const std::optional<std::string>& layers,
         std::optional<std::int64_t> photons, std::int64_t seed, std::int64_t threads,
         const std::optional<double> curvature_max, const std::optional<double> width_max, std::optional<int> taps,
         const py::object& range, const std::optional<double> band, std::optional<int> count,
         const std::optional<double> pixel, std::optional<double> g, std::optional<double> eta, const std::string& db) {
        cli::LutOptions o;
        if (!medium.is_none()) {
          const auto h = to_medium(medium, db);
          if (h.material) {
            o.medium.material = h.material->name;
            o.medium.db = db;
          } else {
            const auto list = [&](const std::vector<double>& v, bool coefficient) {
              std::string s;
              for (double x : v)
                s += (s.empty() ? "" : ",") + format_number(coefficient ? coefficient_from_per_mm(x, h.unit) : x);
              return s;
            };
            o.medium.sigma_a = list(h.medium.sigma_a, true);
            o.medium.sigma_s = list(h.medium.sigma_s, true);
            o.medium.g = list(h.medium.g, false);
            o.medium.eta = format_number(h.medium.eta);
            std::string names;
            for (const auto& c : h.medium.channel_names) names += (names.empty() ? "" : ",") + c;
            o.medium.channels = names;
          }
          o.medium.unit = std::string(symbol(unit ? parse_length_unit(*unit) : h.unit));
        } else {
          if (unit) o.medium.unit = *unit;
          if (g) o.medium.g = format_number(*g);
          if (eta) o.medium.eta = format_number(*eta);
        }
        o.kind = kind;
        o.model = model;
        o.model_given = !model.empty();
        o.accuracy = number_text(accuracy);
        o.tolerance = number_text(tolerance);
        o.energy = number_text(energy);
        o.interpolation = interpolation.value_or("");
        o.layout = layout;
        o.size = size.value_or("");
        o.size_given = size.has_value();
        o.table_tolerance = number_text(table_tolerance);
        if (!thickness.is_none()) {
          std::string list;
          for (double d : to_vector(thickness, "thickness")) list += (list.empty() ? "" : ",") + format_number(d);
          o.thickness = list;
        }
        o.d_min = number_text(d_min);
        o.d_max = number_text(d_max);
        o.samples = samples;
        o.reference = reference;
        o.reference_everywhere = reference_everywhere;
        o.layers = layers.value_or("");
        o.photons_given = photons.has_value();
        o.photons = photons ? checked_count(*photons, "photons", 1, 10'000'000'000) : 0;
        o.seed = checked_count(seed, "seed", 0, INT64_MAX);
        o.threads = static_cast<unsigned>(checked_count(threads, "threads", 0, 4096));
        o.curvature_max = number_text(curvature_max);
        o.width_max = number_text(width_max);
        o.taps = taps.value_or(0);
        o.taps_given = taps.has_value();
        if (!range.is_none()) {
          o.range = number_or_text(range, "range");
          o.range_given = true;
        }
        o.band = number_text(band);
        o.count = count.value_or(0);
        o.count_given = count.has_value();
        o.pixel = number_text(pixel);
        o.quiet = true;
        try {
          const auto& table_kind = cli::table_kind(kind);
          py::gil_scoped_release release;
          return Table{table_kind.build(o)};
        } catch (const InvalidInput& e) {
          rethrow_with_keywords(e);
        }
      },
      py::arg("medium") = py::none(), py::arg("kind") = "radial", py::arg("model") = "", py::kw_only(),
      py::arg("accuracy") = py::none(), py::arg("unit") = py::none(), py::arg("tolerance") = py::none(),
      py::arg("energy") = py::none(), py::arg("interpolation") = py::none(), py::arg("layout") = "pbrt",
      py::arg("size") = py::none(), py::arg("table_tolerance") = py::none(), py::arg("thickness") = py::none(),
      py::arg("d_min") = py::none(), py::arg("d_max") = py::none(), py::arg("samples") = 0,
      py::arg("reference") = false, py::arg("reference_everywhere") = false, py::arg("layers") = py::none(),
      py::arg("photons") = py::none(), py::arg("seed") = 1, py::arg("threads") = 1,
      py::arg("curvature_max") = py::none(), py::arg("width_max") = py::none(), py::arg("taps") = py::none(),
      py::arg("range") = py::none(), py::arg("band") = py::none(), py::arg("count") = py::none(),
      py::arg("pixel") = py::none(), py::arg("g") = py::none(), py::arg("eta") = py::none(), py::arg("db") = "",
      R"(A lookup table of any `bssrdf lut` kind: radial, albedo-radius, transmission, preintegrated, penumbra,
separable, gaussians. Keywords are the command's flags (--table-tolerance -> table_tolerance; size="256x256";
lengths in the medium's unit). Returns a Table: arrays, metadata, and .write("t.exr") as `-o t.exr`.)");
  m.attr("lut_kinds") = [] {
    std::vector<std::string> names;
    for (const auto& k : cli::table_kinds()) names.emplace_back(k.name);
    return names;
  }();

  // ---- advise ----
  py::class_<AdviseCandidate>(m, "AdviseCandidate", "A representation judged by its image-space error and cost.")
      .def_readonly("representation", &AdviseCandidate::representation)
      .def_property_readonly(
          "error", [](const AdviseCandidate& c) { return c.image.error; },
          "predicted image error, 8-bit sRGB code values")
      .def_readonly("cost", &AdviseCandidate::cost, "ns per evaluation")
      .def_readonly("memory_bytes", &AdviseCandidate::memory_bytes)
      .def_readonly("realtime", &AdviseCandidate::realtime)
      .def_readonly("meets_tolerance", &AdviseCandidate::meets_tolerance)
      .def_readonly("parameters", &AdviseCandidate::parameters)
      .def("__repr__", [](const AdviseCandidate& c) { return "<AdviseCandidate " + c.representation + ">"; });
  py::class_<AdviceResult>(m, "Advice",
                           "The cheapest representation that looks right at a pixel size (`bssrdf advise`).")
      .def_property_readonly(
          "candidates", [](const AdviceResult& a) { return a.advice.candidates; }, "cheapest first")
      .def_property_readonly(
          "choice",
          [](const AdviceResult& a) -> py::object {
            if (!a.advice.choice) return py::none();
            return py::cast(a.advice.candidates[*a.advice.choice]);
          },
          "the cheapest within the tolerance for the target, or None")
      .def_property_readonly("reference", [](const AdviceResult& a) { return a.advice.reference; })
      .def_property_readonly("reference_sources", [](const AdviceResult& a) { return a.advice.reference_sources; })
      .def_property_readonly("reference_uncertainty",
                             [](const AdviceResult& a) { return a.advice.reference_uncertainty.error(); })
      .def(
          "to_json", [](const AdviceResult& a) { return to_json(a.advice, a.name); },
          "The JSON `advise -f json` prints.")
      .def("__str__", [](const AdviceResult& a) { return to_table(a.advice, a.name); });
  m.def(
      "advise",
      [](const py::object& medium, double pixel, double tolerance, const std::string& target,
         std::optional<double> object_size, const std::string& reference, std::int64_t photons, std::int64_t seed,
         std::int64_t threads, const std::optional<std::string>& unit, const std::string& db) {
        const auto h = to_medium(medium, db);
        const auto u = output_unit(unit, h);
        AdviseOptions a;
        if (!(pixel > 0 && std::isfinite(pixel))) throw InvalidInput("pixel", format_number(pixel), "a length > 0");
        a.pixel = to_mm(pixel, u);
        if (!(tolerance > 0 && std::isfinite(tolerance)))
          throw InvalidInput("tolerance", format_number(tolerance), "> 0 (8-bit sRGB code values)");
        a.tolerance = tolerance;
        a.target = parse_advise_target(target);
        if (object_size) {
          if (!(*object_size > 0 && std::isfinite(*object_size)))
            throw InvalidInput("object_size", format_number(*object_size), "a length > 0");
          a.object_size = to_mm(*object_size, u);
        }
        const MonteCarloReferenceOptions mc{checked_count(photons, "photons", 1000, 10'000'000'000),
                                            checked_count(seed, "seed", 0, INT64_MAX),
                                            static_cast<unsigned>(checked_count(threads, "threads", 0, 4096))};
        std::unique_ptr<ReferenceProfile> ref;
        if (reference == "montecarlo") {
          ref = std::make_unique<MonteCarloReference>(mc);
        } else if (reference == "auto") {
          ref = std::make_unique<AutoReference>(mc);
        } else if (reference == "exact") {
          const auto exact = make_model("exact");
          for (std::size_t c = 0; c < h.medium.channels(); ++c)
            if (const auto report = exact->validity(h.medium.reduced(c)); worst(report) == Severity::invalid)
              throw InvalidInput("reference", "exact",
                                 "media inside the exact table (channel " + h.medium.channel_names[c] + ": " +
                                     report.front().message + "); use reference='auto' or 'montecarlo'");
          ref = std::make_unique<ModelReference>(make_model("exact"));
        } else {
          throw InvalidInput("reference", "'" + reference + "'", "auto, exact or montecarlo");
        }
        AdviceResult out{{}, h.material ? h.material->name : "medium"};
        py::gil_scoped_release release;
        out.advice = advise(h.medium, *ref, a);
        return out;
      },
      py::arg("medium"), py::kw_only(), py::arg("pixel"), py::arg("tolerance") = 1.0, py::arg("target") = "any",
      py::arg("object_size") = py::none(), py::arg("reference") = "auto", py::arg("photons") = 200000,
      py::arg("seed") = 1, py::arg("threads") = 0, py::arg("unit") = py::none(), py::arg("db") = "",
      "The cheapest representation of a medium that looks right at a pixel size (in the medium's unit): `bssrdf "
      "advise`. target: realtime, offline or any; reference: auto, exact or montecarlo.");
}

}  // namespace bssrdf::python
