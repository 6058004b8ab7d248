// The table kinds built through the library's entry points (lut/table_kinds.hpp), without the command
// line: each one is byte for byte the table `bssrdf lut --kind K` writes for the same options (the
// command only parses its flags into these options), and its summary says what it built and how well.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>

#include "bssrdf/error.hpp"
#include "bssrdf/io/layers_json.hpp"
#include "bssrdf/lut/table_kinds.hpp"
#include "bssrdf/materials.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_choice.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/models/exact.hpp"
#include "cli_runner.hpp"

namespace {

using namespace bssrdf;
constexpr auto npos = std::string::npos;

const Material& skin1() {
  static const auto database = MaterialDatabase::load(default_materials_dir());
  return database.find("Skin1");
}

// Skin1 under a model, in mm: the context a profile kind tabulates.
struct Skin1 {
  // By default the registry's default model: what `bssrdf lut` takes without --model.
  explicit Skin1(const std::string& model_name = default_model(skin1().medium).name) : model(make_model(model_name)) {}
  std::unique_ptr<Model> model;
  TableContext context() const { return {skin1(), &skin1().medium, model.get(), LengthUnit::millimetre}; }
};

// What `bssrdf lut ARGS` writes as JSON (or in the format FILE_NAME's extension names).
std::string written_by_cli(const std::string& args, const std::string& file_name = "table.json") {
  const auto file = test_cli::temp(file_name);
  const auto r = test_cli::run("lut " + args + " -q -o " + file.string());
  EXPECT_EQ(r.status, 0) << args << ": " << r.err;
  return test_cli::slurp(file);
}

double attribute_number(const LookupTable& table, const std::string& name) {
  const auto* value = table.attribute(name);
  if (value == nullptr || !std::holds_alternative<double>(*value)) {
    ADD_FAILURE() << "no number " << name;
    return 0;
  }
  return std::get<double>(*value);
}

TEST(TableKinds, RadialIsTheTableTheCommandWrites) {
  const Skin1 skin;
  const auto built = tabulate_radial(skin.context(), {});
  EXPECT_EQ(to_json(built.table), written_by_cli("--material Skin1"));
  EXPECT_EQ(built.table.kind, "radial");
  EXPECT_EQ(built.summary.rfind("radial table: ", 0), 0u) << built.summary;
  EXPECT_NE(built.summary.find("<= tolerance 0.001"), npos) << built.summary;  // its error against its bound
}

// Sized by an image tolerance: the table records its image error, which meets the tolerance it says it meets.
TEST(TableKinds, RadialSizedByAnImageToleranceRecordsItsError) {
  const Skin1 skin;
  RadialKindOptions options;
  options.image = ImageErrorCheck{0.5, 2.0};
  const auto built = tabulate_radial(skin.context(), options);
  EXPECT_EQ(to_json(built.table), written_by_cli("--material Skin1 --pixel 0.5 --tolerance 2"));
  EXPECT_LE(attribute_number(built.table, "bssrdf:image_error"), 2.0);
  EXPECT_EQ(attribute_number(built.table, "bssrdf:image_error_pixel_mm"), 0.5);
  EXPECT_NE(built.summary.find("image error at 0.5 mm pixels"), npos) << built.summary;
  EXPECT_NE(built.summary.find("chosen for --tolerance 2 code values"), npos) << built.summary;
}

TEST(TableKinds, ReferenceRadialOfAMediumAndOfALayerStack) {
  ReferenceRadialOptions options;
  options.photons = 20000;
  options.seed = 3;
  const auto half_space =
      tabulate_reference_radial({skin1(), &skin1().medium, nullptr, LengthUnit::millimetre}, options);
  EXPECT_EQ(to_json(half_space.table), written_by_cli("--material Skin1 --reference --photons 20000 --seed 3"));
  EXPECT_NE(half_space.summary.find("Monte Carlo reference"), npos) << half_space.summary;
  EXPECT_NE(half_space.summary.find(" +- "), npos) << half_space.summary;  // its standard errors

  const std::string path = std::string(BSSRDF_TEST_DATA) + "/two_layer_skin.json";
  const auto file = read_layers_json(path);
  options.photons = 5000;
  options.seed = 1;
  const auto stack = tabulate_reference_radial(file.stack, path, {std::nullopt, nullptr, nullptr, file.unit}, options);
  EXPECT_EQ(to_json(stack.table), written_by_cli("--reference --layers " + path + " --photons 5000"));
  EXPECT_EQ(std::get<std::string>(*stack.table.attribute("bssrdf:layers")), path + " (2 layers)");
}

TEST(TableKinds, AlbedoRadiusFamilyLayout) {
  AlbedoRadiusKindOptions options;
  options.g = 0.5;
  options.eta = 1.4;
  options.layout = AlbedoRadiusLayoutRule::family;
  options.albedos = 12;
  options.radii = 10;
  options.table.shape = RowShape::exact;  // the command's default at this g and eta (the registry's)
  const auto built = tabulate_albedo_radius(options);
  EXPECT_EQ(to_json(built.table),
            written_by_cli("--kind albedo-radius --layout family --size 12x10 --g 0.5 --eta 1.4"));
  EXPECT_EQ(built.table.width, 10u);
  EXPECT_EQ(built.table.height, 12u);
  EXPECT_EQ(built.summary.rfind("albedo-radius table (family layout): 12 albedos x 10 radii", 0), 0u) << built.summary;
}

// `--model exact`: the rows from the exact model, and the header says so; the default records that
// its rows carry the radiative-transfer total; other models are refused in one line.
TEST(TableKinds, AlbedoRadiusExactRowsAndTheRecordedEnergy) {
  AlbedoRadiusKindOptions options;
  options.g = 0.5;
  options.eta = 1.4;
  options.table.shape = RowShape::exact;
  const auto built = tabulate_albedo_radius(options);
  EXPECT_EQ(to_json(built.table), written_by_cli("--kind albedo-radius --model exact --g 0.5 --eta 1.4"));
  EXPECT_EQ(std::get<std::string>(*built.table.attribute("bssrdf:model")), "exact");
  EXPECT_NE(std::get<std::string>(*built.table.attribute("bssrdf:profile")).find("exact model"), npos);
  std::size_t inside = 0;
  for (double rho : AlbedoRadiusLayout::pbrt().albedo) {
    const auto m = reduced_unit_extinction(rho, 0.5, 1.4);
    inside += rho > 0 && exact_domain(bundled_exact_table(), m.albedo_prime, m.g, m.eta).empty();
  }
  EXPECT_GE(inside, 97u);
  EXPECT_NE(built.summary.find("the exact model (radiative transfer) in " + std::to_string(inside) + " of 100 rows"),
            npos)
      << built.summary;
  const auto pbd = tabulate_albedo_radius({});
  EXPECT_NE(std::get<std::string>(*pbd.table.attribute("bssrdf:effective_albedo")).find("radiative-transfer total"),
            npos);
  const auto r = test_cli::run("lut --kind albedo-radius --model dipole -o " + test_cli::temp("refused.json").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("pbd (photon beam diffusion, as pbrt) or exact"), npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(test_cli::temp("refused.json")));
}

// An albedo-radius table serves one g: for a material whose channels' g differ it says which one it took.
TEST(TableKinds, AlbedoRadiusSaysWhichGItTookFromAMaterial) {
  const auto path = test_cli::temp("milk-albedo-radius.json");
  const auto differing = test_cli::run("lut --kind albedo-radius --material \"Lowfat Milk\" -o " + path.string());
  ASSERT_EQ(differing.status, 0) << differing.err;
  EXPECT_NE(test_cli::slurp(path).find("\"bssrdf:g_choice\": \"g differs between the channels (0.859 to 0.932): the "
                                       "table is for the first channel's g = 0.932"),
            npos);
  EXPECT_NE(differing.out.find("the first channel's g = 0.932"), npos) << differing.out;
  ASSERT_EQ(test_cli::run("lut --kind albedo-radius --material Skin1 -o " + path.string()).status, 0);
  EXPECT_EQ(test_cli::slurp(path).find("bssrdf:g_choice"), npos);
}

TEST(TableKinds, TransmissionSaysWhichSolverMadeIt) {
  TransmissionTableOptions options;
  options.model = "adding-doubling";
  const auto built =
      tabulate_transmission({skin1(), &skin1().medium, nullptr, LengthUnit::millimetre}, {0.5, 1, 2}, options);
  EXPECT_EQ(to_json(built.table), written_by_cli("--kind transmission --material Skin1 --thickness 0.5,1,2"));
  EXPECT_EQ(std::get<std::string>(*built.table.attribute("bssrdf:model_description")),
            "total transmittance of slabs: adding-doubling (exact)");
  EXPECT_EQ(std::get<std::string>(*built.table.attribute("bssrdf:model")), "adding-doubling");
  options.model = "multipole";
  const auto multipole =
      tabulate_transmission({skin1(), &skin1().medium, nullptr, LengthUnit::millimetre}, {5}, options);
  EXPECT_EQ(std::get<std::string>(*multipole.table.attribute("bssrdf:model")), "multipole");
  EXPECT_NE(built.summary.find("3 thicknesses"), npos) << built.summary;
  EXPECT_NE(built.summary.find("(3 adding-doubling, 0 Monte Carlo"), npos) << built.summary;
}

TEST(TableKinds, PreintegratedAndPenumbra) {
  const Skin1 skin;
  PreintegratedKindOptions preintegrated;
  preintegrated.table.width = 32;
  preintegrated.table.height = 16;
  preintegrated.table.curvature_max = 2;
  auto built = tabulate_preintegrated(skin.context(), preintegrated);
  EXPECT_EQ(to_json(built.table),
            written_by_cli("--kind preintegrated --material Skin1 --size 32x16 --curvature-max 2"));
  EXPECT_EQ(built.summary.rfind("pre-integrated table: 32 N.L x 16 curvatures", 0), 0u) << built.summary;

  PenumbraOptions penumbra;
  penumbra.width = 32;
  penumbra.height = 16;
  penumbra.width_max = 5;
  built = tabulate_penumbra(skin.context(), penumbra);
  EXPECT_EQ(to_json(built.table), written_by_cli("--kind penumbra --material Skin1 --size 32x16 --width-max 5"));
  EXPECT_EQ(built.summary.rfind("penumbra table: 32 shadow values x 16 penumbra widths", 0), 0u) << built.summary;
}

TEST(TableKinds, SeparableKernelAndItsShaders) {
  const Skin1 skin;
  SeparableKindOptions options;
  options.kernel.band = 0.99;
  const auto built = tabulate_separable(skin.context(), options);
  EXPECT_EQ(to_json(built.table), written_by_cli("--kind separable --material Skin1 --band 0.99"));
  EXPECT_EQ(built.other_formats.at("glsl")(),
            written_by_cli("--kind separable --material Skin1 --band 0.99", "kernel.glsl"));
  EXPECT_NE(built.summary.find("holding 99 % of the widest channel's light"), npos) << built.summary;

  // Two channels: the table is built, a shader (three channels) is refused when asked for, naming the field.
  Medium two = skin1().medium;
  two.sigma_a.resize(2);
  two.sigma_s.resize(2);
  two.g.resize(2);
  two.channel_names = {"a", "b"};
  const auto two_channels = tabulate_separable({std::nullopt, &two, skin.model.get(), LengthUnit::millimetre}, {});
  EXPECT_EQ(two_channels.table.kind, "separable");
  try {
    two_channels.other_formats.at("hlsl")();
    ADD_FAILURE() << "an HLSL kernel of two channels";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.field(), "format");
  }
}

TEST(TableKinds, GaussiansFittedOrTheModelsOwn) {
  GaussiansKindOptions options;
  options.count = 3;
  const auto fitted = tabulate_gaussians(Skin1().context(), options);
  EXPECT_EQ(to_json(fitted.table), written_by_cli("--kind gaussians --material Skin1 --count 3"));
  EXPECT_NE(fitted.summary.find("3 Gaussians"), npos) << fitted.summary;
  EXPECT_NE(fitted.summary.find("relative L2 error"), npos) << fitted.summary;

  const Skin1 quantized("quantized");
  const auto own = tabulate_gaussians(quantized.context(), {});
  EXPECT_EQ(to_json(own.table), written_by_cli("--kind gaussians --material Skin1 --model quantized"));
  EXPECT_NE(own.summary.find("the model's own mixture"), npos) << own.summary;

  options.count = 33;
  EXPECT_THROW(tabulate_gaussians(Skin1().context(), options), InvalidInput);
}

}  // namespace
