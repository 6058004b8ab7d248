#include "bssrdf/advise/advise_files.hpp"
#include "bssrdf/model_registry.hpp"

#include <algorithm>
#include <cmath>

#include "bssrdf/error.hpp"
#include "bssrdf/image/realtime_tables.hpp"
#include "bssrdf/io/atomic_file.hpp"
#include "bssrdf/layers.hpp"
#include "bssrdf/lut/gaussian_mixture_table.hpp"
#include "bssrdf/lut/preintegrated_table.hpp"
#include "bssrdf/lut/radial_table.hpp"
#include "bssrdf/lut/reference_radial_table.hpp"
#include "bssrdf/lut/separable_kernel.hpp"
#include "bssrdf/lut/table_context.hpp"

namespace bssrdf {

std::filesystem::path write_advised_file(const std::filesystem::path& dir, const std::string& stem,
                                         const Medium& medium, const std::optional<Material>& material,
                                         const Advice& advice, const MonteCarloReferenceOptions& reference) {
  if (!advice.choice)
    throw InvalidInput("--write: no candidate meets the tolerance for this target, so there is nothing to write");
  const AdviseCandidate& chosen = advice.candidates[*advice.choice];
  const std::string representation = chosen.representation;
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error || !std::filesystem::is_directory(dir))
    throw InvalidInput("--write", "'" + dir.string() + "'", "a directory that can be created");
  std::string name = representation;
  std::replace(name.begin(), name.end(), ':', '_');
  const auto path = dir / (stem + "." + name + ".json");

  const auto colon = representation.find(':');
  const std::string head = representation.substr(0, colon);
  std::unique_ptr<Model> model;
  if (colon != std::string::npos) model = make_model(representation.substr(colon + 1));
  TableContext context;
  context.material = material;
  context.medium = &medium;
  context.model = model.get();
  LookupTable table;
  if (representation == "lambertian") {
    table = described_table("albedo", 1, 1, context);
    for (std::size_t c = 0; c < medium.channels(); ++c)
      table.add_channel(medium.channel_names[c], "diffuse reflectance (albedo), per unit entered flux",
                        {advice.diffuse_reflectance[c]});
  } else if (head.rfind("radial-table-", 0) == 0 ||
             (representation == "reference-table" && !advice.reference_table.empty())) {
    // The nodes of radial_table(), exactly as the advice judged them: of the model, or of the reference.
    std::vector<RadialTableNodes> nodes;
    if (representation == "reference-table")
      nodes = advice.reference_table;
    else
      for (std::size_t c = 0; c < medium.channels(); ++c)
        nodes.push_back(radial_table_nodes(*model, medium.reduced(c), std::stoul(head.substr(13))));
    std::size_t n = 0;
    for (const auto& channel : nodes) n = std::max(n, channel.radius.size());
    table = described_table("radial-log", n, 1, context);
    table.set("bssrdf:interpolation", "linear in (ln r, ln R); R(r_0) below r_0, 0 beyond r_{N-1}");
    for (std::size_t c = 0; c < medium.channels(); ++c) {
      table.add_channel("radius." + medium.channel_names[c], "radius, mm", nodes[c].radius);
      table.add_channel(medium.channel_names[c], "R(r), 1/mm^2, per unit entered flux", nodes[c].value);
    }
  } else if (head.rfind("separable-", 0) == 0 || head.rfind("preintegrated-", 0) == 0) {
    const auto parameter = [&](const std::string& key) {
      for (const auto& [k, v] : chosen.parameters)
        if (k == key) return v;
      throw InvalidInput("advice parameter", key, "recorded by advise()");
    };
    if (head[0] == 's') {
      SeparableKernelOptions options;
      options.taps = static_cast<int>(parameter("taps"));
      options.range = parameter("range_mm");
      options.band = parameter("band");
      table = to_lookup_table(build_separable_kernel(medium, *model, options), context);
    } else {
      PreintegratedOptions options;
      options.width = options.height = static_cast<std::size_t>(parameter("size"));
      options.curvature_max = parameter("curvature_max_per_mm");
      table = to_lookup_table(build_preintegrated_table(medium, *model, options), context);
    }
  } else if (head.rfind("gaussians-", 0) == 0) {
    table =
        to_lookup_table(fitted_mixture_table(medium, *model, std::stoi(head.substr(10)), kGaussianFitSamples), context);
  } else if (representation == "reference-table") {
    ReferenceRadialOptions options;
    options.photons = reference.photons;
    options.seed = reference.seed;
    options.threads = reference.threads;
    table = to_lookup_table(build_reference_radial_table(LayerStack::half_space(medium), options), context);
  } else {
    model = make_model(representation);
    context.model = model.get();
    table = to_lookup_table(build_radial_table(medium, *model, {}), context);
  }
  table.set("bssrdf:advice", representation + " at " + format_number(advice.options.pixel) +
                                 " mm per pixel: image error " + format_number(chosen.image.error) +
                                 " code values (tolerance " + format_number(advice.options.tolerance) + ") against " +
                                 advice.reference);
  table.set("bssrdf:image_error", chosen.image.error);
  table.set("bssrdf:image_error_pixel_mm", advice.options.pixel);
  write_file_atomically(path, to_json(table));
  return path;
}

}  // namespace bssrdf
