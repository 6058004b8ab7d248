// bssrdf.reference (the Monte Carlo reference, `bssrdf reference`) and bssrdf.slab (adding-doubling,
// `bssrdf slab`): results as arrays, per unit incident flux as the CLI reports them.
#include <cmath>

#include "bindings.hpp"
#include "bssrdf/adding_doubling/slab.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/io/layers_json.hpp"
#include "bssrdf/layers.hpp"
#include "bssrdf/montecarlo.hpp"
#include "interruptible.hpp"

namespace bssrdf::python {
namespace {

// A medium's half-space or slab, or a layer stack file; the unit of outputs.
std::pair<LayerStack, LengthUnit> stack_of(const py::object& medium, const std::optional<double>& thickness,
                                           const std::optional<std::string>& layers,
                                           const std::optional<std::string>& unit, const std::string& db) {
  if (layers) {
    if (!medium.is_none()) throw InvalidInput("layers describes the medium: give medium=None with it");
    if (thickness) throw InvalidInput("thickness: not with layers (the file gives the thicknesses)");
    const auto file = read_layers_json(*layers);
    return {file.stack, unit ? parse_length_unit(*unit) : file.unit};
  }
  const auto h = to_medium(medium, db);
  const auto u = output_unit(unit, h);
  double d = kSemiInfinite;
  if (thickness) {
    if (!(*thickness > 0 && std::isfinite(*thickness)))
      throw InvalidInput("thickness", format_number(*thickness), "> 0 and finite (None: semi-infinite)");
    d = to_mm(*thickness, u);
  }
  LayerStack stack = LayerStack::slab(h.medium, d);
  if (h.material) stack.layers[0].name = h.material->name;
  return {stack, u};
}

struct ReferenceResult {
  MonteCarloResult result;
  LengthUnit unit;
};

Array channel_field(const ReferenceResult& r, double ChannelResult::*field) {
  std::vector<double> v;
  for (const auto& c : r.result.channels) v.push_back(c.*field);
  return to_array(v);
}

py::tuple estimate_field(const ReferenceResult& r, Estimate ChannelResult::*field) {
  std::vector<double> value, error;
  for (const auto& c : r.result.channels) {
    value.push_back((c.*field).value);
    error.push_back((c.*field).standard_error);
  }
  return py::make_tuple(to_array(value), to_array(error));
}

Array radial(const ReferenceResult& r, std::vector<double> ChannelResult::*field, double area_power) {
  const double mm = millimetres_per(r.unit);
  std::vector<std::vector<double>> rows;
  for (const auto& c : r.result.channels) {
    rows.push_back(c.*field);
    for (double& v : rows.back()) v *= std::pow(mm, area_power);
  }
  return to_array(rows);
}

struct SlabResult {
  std::vector<std::string> channels;
  std::vector<adding_doubling::Totals> totals;
  adding_doubling::Incidence incidence;
};

Array totals_field(const SlabResult& s, const std::function<double(const adding_doubling::Totals&)>& f) {
  std::vector<double> v;
  for (const auto& t : s.totals) v.push_back(f(t));
  return to_array(v);
}

}  // namespace

void bind_reference(py::module_& m) {
  py::class_<ReferenceResult>(m, "Reference",
                              R"(A Monte Carlo run (`bssrdf reference`): per channel, per unit incident flux.

Totals are (value, standard error) pairs of arrays; reflectance is channels x bins (1/unit^2) at
bin_radius (unit).)")
      .def_property_readonly("channels",
                             [](const ReferenceResult& r) {
                               std::vector<std::string> names;
                               for (const auto& c : r.result.channels) names.push_back(c.name);
                               return names;
                             })
      .def_property_readonly("unit", [](const ReferenceResult& r) { return std::string(symbol(r.unit)); })
      .def_property_readonly(
          "specular_reflectance",
          [](const ReferenceResult& r) { return channel_field(r, &ChannelResult::specular_reflectance); })
      .def_property_readonly(
          "diffuse_reflectance",
          [](const ReferenceResult& r) { return estimate_field(r, &ChannelResult::diffuse_reflectance); },
          "(value, stderr) per channel, specular excluded")
      .def_property_readonly(
          "total_transmittance",
          [](const ReferenceResult& r) { return estimate_field(r, &ChannelResult::total_transmittance); })
      .def_property_readonly("absorbed",
                             [](const ReferenceResult& r) { return estimate_field(r, &ChannelResult::absorbed); })
      .def_property_readonly(
          "single_scattering_reflectance",
          [](const ReferenceResult& r) { return estimate_field(r, &ChannelResult::single_scattering_reflectance); })
      .def_property_readonly("bin_radius",
                             [](const ReferenceResult& r) {
                               std::vector<double> v;
                               for (double x : r.result.bin_radius) v.push_back(from_mm(x, r.unit));
                               return to_array(v);
                             })
      .def_property_readonly("bin_inner",
                             [](const ReferenceResult& r) {
                               std::vector<double> v;
                               for (double x : r.result.bin_inner) v.push_back(from_mm(x, r.unit));
                               return to_array(v);
                             })
      .def_property_readonly("bin_outer",
                             [](const ReferenceResult& r) {
                               std::vector<double> v;
                               for (double x : r.result.bin_outer) v.push_back(from_mm(x, r.unit));
                               return to_array(v);
                             })
      .def_property_readonly(
          "reflectance", [](const ReferenceResult& r) { return radial(r, &ChannelResult::reflectance, 2); },
          "R(r) per bin, channels x bins, 1/unit^2")
      .def_property_readonly("reflectance_stderr",
                             [](const ReferenceResult& r) { return radial(r, &ChannelResult::reflectance_stderr, 2); })
      .def_property_readonly("transmittance",
                             [](const ReferenceResult& r) { return radial(r, &ChannelResult::transmittance, 2); })
      .def_property_readonly("photons", [](const ReferenceResult& r) { return r.result.options.photons; })
      .def_property_readonly("seed", [](const ReferenceResult& r) { return r.result.options.seed; })
      .def_property_readonly("seconds", [](const ReferenceResult& r) { return r.result.seconds; })
      .def(
          "report", [](const ReferenceResult& r) { return r.result.report(r.unit); }, "The full report for people.")
      .def(
          "to_json", [](const ReferenceResult& r) { return to_json(r.result, r.unit); },
          "The JSON `bssrdf reference -f json` prints (both normalisations).")
      .def("to_csv", [](const ReferenceResult& r) { return to_csv(r.result, r.unit); })
      .def("__str__", [](const ReferenceResult& r) { return r.result.report(r.unit); })
      .def("__repr__", [](const ReferenceResult& r) {
        return "<Reference " + std::to_string(r.result.channels.size()) + " channels, " +
               std::to_string(r.result.options.photons) + " photons each>";
      });

  m.def(
      "reference",
      [](const py::object& medium, std::int64_t photons, std::optional<double> thickness,
         const std::optional<std::string>& layers, std::int64_t seed, std::int64_t threads, std::optional<double> r_max,
         std::optional<double> r_min, std::int64_t bins, const std::string& spacing, std::int64_t depth_bins,
         const std::optional<std::string>& unit, const py::object& progress, const std::string& db) {
        auto [stack, u] = stack_of(medium, thickness, layers, unit, db);
        MonteCarloOptions options;
        // The command line's ranges (cli_common.hpp: kMaxPhotons, kMaxSeed, kMaxThreads, kMaxBins).
        options.photons = checked_count(photons, "photons", 1, 10'000'000'000);
        options.seed = checked_count(seed, "seed", 0, INT64_MAX);
        options.threads = static_cast<unsigned>(checked_count(threads, "threads", 0, 4096));
        options.bins = checked_count(bins, "bins", 2, 10'000'000);
        if (spacing != "linear" && spacing != "log")
          throw InvalidInput("spacing", "'" + spacing + "'", "linear or log");
        options.spacing = spacing == "log" ? BinSpacing::log : BinSpacing::linear;
        options.depth_bins = checked_count(depth_bins, "depth_bins", 0, 10'000'000);
        if (r_max) {
          options.r_max = to_mm(*r_max, u);
          if (!(options.r_max >= 1e-9 * static_cast<double>(options.bins)))
            throw InvalidInput("r_max", format_number(*r_max), "> 0 and at least 1e-9 mm per bin");
        }
        if (r_min) {
          options.r_min = to_mm(*r_min, u);
          if (!(options.r_min >= 1e-9)) throw InvalidInput("r_min", format_number(*r_min), "> 0 and at least 1e-9 mm");
        }
        options.validate();
        stack.validate();
        const std::function<MonteCarloResult(const std::function<void(std::uint64_t, std::uint64_t)>&)> work =
            [&](const auto& hook) {
              MonteCarloOptions o = options;
              o.progress = hook;
              return run_monte_carlo(stack, o);
            };
        return ReferenceResult{run_interruptibly(work, progress), u};
      },
      py::arg("medium") = py::none(), py::arg("photons") = 1000000, py::kw_only(), py::arg("thickness") = py::none(),
      py::arg("layers") = py::none(), py::arg("seed") = 1, py::arg("threads") = 0, py::arg("r_max") = py::none(),
      py::arg("r_min") = py::none(), py::arg("bins") = 100, py::arg("spacing") = "linear", py::arg("depth_bins") = 0,
      py::arg("unit") = py::none(), py::arg("progress") = py::none(), py::arg("db") = "",
      R"(The Monte Carlo reference (`bssrdf reference`): the radiative transfer equation solved by tracing photons.

medium: a Medium, Material or name (half-space, or a slab with thickness=), or layers="stack.json";
photons per channel; the result depends on (inputs, seed) only, never on threads (0: all cores).
progress: called as progress(done, total) on the calling thread about every 50 ms. Ctrl-C stops
the run cleanly (KeyboardInterrupt after the running batches finish); so does an exception raised
by progress.)");

  py::class_<SlabResult>(m, "SlabTotals", "Adding-doubling totals of a slab (`bssrdf slab`), per unit incident flux.")
      .def_readonly("channels", &SlabResult::channels)
      .def_property_readonly("incidence",
                             [](const SlabResult& s) { return std::string(adding_doubling::to_string(s.incidence)); })
      .def_property_readonly(
          "diffuse_reflectance",
          [](const SlabResult& s) { return totals_field(s, [](const auto& t) { return t.diffuse_reflectance; }); },
          "specular excluded")
      .def_property_readonly(
          "specular_reflectance",
          [](const SlabResult& s) { return totals_field(s, [](const auto& t) { return t.specular_reflectance; }); })
      .def_property_readonly(
          "total_transmittance",
          [](const SlabResult& s) { return totals_field(s, [](const auto& t) { return t.total_transmittance; }); },
          "unscattered beam included")
      .def_property_readonly("unscattered_transmittance",
                             [](const SlabResult& s) {
                               return totals_field(s, [](const auto& t) { return t.unscattered_transmittance; });
                             })
      .def_property_readonly(
          "absorbed", [](const SlabResult& s) { return totals_field(s, [](const auto& t) { return t.absorbed(); }); })
      .def_property_readonly(
          "entered_scale",
          [](const SlabResult& s) { return totals_field(s, [](const auto& t) { return t.entered_scale(); }); },
          "1 / (1 - R_specular): multiply by it for per entered flux")
      .def_property_readonly(
          "points",
          [](const SlabResult& s) {
            std::vector<int> v;
            for (const auto& t : s.totals) v.push_back(t.points);
            return v;
          },
          "quadrature angles per hemisphere")
      .def_property_readonly("error_estimate", [](const SlabResult& s) {
        return totals_field(s, [](const auto& t) { return t.error_estimate; });
      });

  m.def(
      "slab",
      [](const py::object& medium, std::optional<double> thickness, const std::optional<std::string>& layers,
         std::optional<std::pair<double, double>> slides, const std::string& incidence, double tolerance, int points,
         const std::optional<std::string>& unit, const std::string& db) {
        auto [stack, u] = stack_of(medium, thickness, layers, unit, db);
        if (!(tolerance >= 1e-8 && tolerance <= 0.1))
          throw InvalidInput("tolerance", format_number(tolerance), "1e-8 to 0.1");
        if (points != 0 && !(points >= 4 && points <= 256))
          throw InvalidInput("points", std::to_string(points), "4 to 256");
        const auto light = adding_doubling::parse_incidence(incidence);
        if (slides) {
          const auto [n, d] = *slides;
          if (!(n >= 1 && n <= 4)) throw InvalidInput("slides index", format_number(n), "1 to 4");
          if (!(d > 0 && std::isfinite(d))) throw InvalidInput("slides thickness", format_number(d), "> 0 and finite");
          if (stack.semi_infinite()) throw InvalidInput("slides: only for a finite slab (give thickness)");
          Layer glass;
          glass.name = "slide";
          glass.n = n;
          glass.thickness = to_mm(d, u);
          glass.sigma_a.assign(stack.channels(), 0);
          glass.sigma_s.assign(stack.channels(), 0);
          glass.g.assign(stack.channels(), 0);
          stack.layers.insert(stack.layers.begin(), glass);
          stack.layers.push_back(glass);
        }
        stack.validate();
        adding_doubling::Options options;
        options.tolerance = tolerance;
        options.points = points;
        SlabResult out{stack.channel_names, {}, light};
        py::gil_scoped_release release;
        for (std::size_t c = 0; c < stack.channels(); ++c)
          out.totals.push_back(adding_doubling::solve(adding_doubling::slab_of(stack, c), light, options));
        return out;
      },
      py::arg("medium") = py::none(), py::kw_only(), py::arg("thickness") = py::none(), py::arg("layers") = py::none(),
      py::arg("slides") = py::none(), py::arg("incidence") = "collimated", py::arg("tolerance") = 1e-4,
      py::arg("points") = 0, py::arg("unit") = py::none(), py::arg("db") = "",
      R"(Exact totals of a slab or layer stack by adding-doubling (`bssrdf slab`).

thickness in the medium's unit (None: semi-infinite), or layers="stack.json"; slides=(index,
thickness): glass on both faces; incidence collimated or diffuse; tolerance on R and T sets the
angles (or points= fixes them).)");
}

}  // namespace bssrdf::python
