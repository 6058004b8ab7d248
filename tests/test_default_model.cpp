// The default profile model (model_choice.hpp: default_model), decided once and taken by every command
// without --model: exact inside its domain, otherwise the most accurate model measured there, with
// the reason in every output; and validity is never hidden (stderr, whatever the format and -q).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "bssrdf/materials.hpp"
#include "bssrdf/model_choice.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/models/diffusion_validity.hpp"
#include "bssrdf/models/exact.hpp"
#include "cli_runner.hpp"

using namespace bssrdf;
using namespace bssrdf::test_cli;

namespace {

const MaterialDatabase& bundled() {
  static const MaterialDatabase db = MaterialDatabase::load(default_materials_dir());
  return db;
}

}  // namespace

TEST(DefaultModel, ExactForEveryBundledMaterial) {
  int materials = 0;
  for (const auto& m : bundled().all()) {
    const auto chosen = default_model(m.medium);
    EXPECT_EQ(chosen.name, "exact") << m.name << ": " << chosen.reason;
    EXPECT_EQ(chosen.reason, "") << m.name;
    ++materials;
  }
  EXPECT_EQ(materials, 47);
}

TEST(DefaultModel, OutsideTheExactDomainTheMostAccurateMeasuredModelWithItsReason) {
  // g < 0 is outside the exact model's domain: the default is the valid candidate with the smallest
  // measured error there (the bands against adding-doubling: documented_total_error), and the reason
  // names the channel, the parameter and the error used.
  const Medium medium = Medium::single_channel(0.05, 2.0, -0.3, 1.3);
  const auto chosen = default_model(medium);
  ASSERT_NE(chosen.name, "exact");
  EXPECT_NE(chosen.reason.find("g = -0.3"), std::string::npos) << chosen.reason;
  EXPECT_NE(chosen.reason.find("most accurate"), std::string::npos) << chosen.reason;
  const auto m = medium.reduced(0);
  const double chosen_error = documented_total_error(measured_limits(chosen.name), m.albedo_prime, m.g);
  for (const auto& e : model_registry()) {
    if (!e.auto_candidate || e.reference_accuracy || !e.limits) continue;
    if (worst(e.make()->validity(m)) == Severity::invalid) continue;
    EXPECT_LE(chosen_error, documented_total_error(*e.limits, m.albedo_prime, m.g)) << e.name;
  }
  // A wrong default would not be the minimum: the test above fails if the rule picks by cost or order.
  EXPECT_EQ(worst(make_model(chosen.name)->validity(m)) == Severity::invalid, false);
}

TEST(DefaultModel, OverAlbedosForFitsAndAlbedoTables) {
  EXPECT_EQ(default_model_over_albedos({0.0, 0.5, 0.9}, 1.3, 1.3).name, "exact");
  EXPECT_EQ(default_model_over_albedos({}, 1.0, 1.6).name, "exact");
  const auto outside = default_model_over_albedos({0.5}, 1.3, 4.0);  // eta 4: beyond every table
  EXPECT_NE(outside.name, "exact");
  EXPECT_NE(outside.reason.find("eta"), std::string::npos) << outside.reason;
}

TEST(DefaultModelCli, EveryProfileCommandTakesTheDefaultAndSaysSo) {
  // profile: JSON model key, table header, CSV comment line.
  const auto json = run("profile --material Skin1 --radii 0.5,1 -f json");
  ASSERT_EQ(json.status, 0) << json.err;
  EXPECT_EQ(nlohmann::json::parse(json.out)["model"], "exact");
  const auto csv = run("profile --material Skin1 --radii 0.5,1 -f csv");
  ASSERT_EQ(csv.status, 0) << csv.err;
  EXPECT_EQ(csv.out.substr(0, csv.out.find('\n')), "# model: exact");
  const auto table = run("profile --material Skin1 --radii 0.5,1");
  EXPECT_EQ(table.out.substr(0, 12), "model     ex");
  // Outside the domain the reason is in every format.
  const auto other = run("profile --sigma-a 0.05 --sigma-s 2 --g -0.3 --radii 0.5,1 -f json");
  ASSERT_EQ(other.status, 0) << other.err;
  const auto doc = nlohmann::json::parse(other.out);
  EXPECT_NE(doc["model"], "exact");
  EXPECT_NE(doc["model_choice"].get<std::string>().find("g = -0.3"), std::string::npos);
  const auto other_csv = run("profile --sigma-a 0.05 --sigma-s 2 --g -0.3 --radii 0.5,1 -f csv");
  EXPECT_NE(other_csv.out.find("# model_choice: default: channel"), std::string::npos) << other_csv.out;

  // lut: the table's metadata (JSON here; EXR carries the same attributes) and its CSV.
  const auto path = temp("skin1.json");
  const auto lut = run("lut --material Skin1 --kind radial -q -o " + path.string());
  ASSERT_EQ(lut.status, 0) << lut.err;
  EXPECT_EQ(nlohmann::json::parse(slurp(path))["attributes"]["bssrdf:model"], "exact");
  const auto kernel = temp("kernel.csv");
  const auto lut_csv = run("lut --material Skin1 --kind separable -q -o " + kernel.string());
  ASSERT_EQ(lut_csv.status, 0) << lut_csv.err;
  const std::string kernel_text = slurp(kernel);
  EXPECT_EQ(kernel_text.substr(0, kernel_text.find('\n')), "# model: exact");
  const auto albedo_radius = temp("ar.json");
  ASSERT_EQ(run("lut --kind albedo-radius --g 0.5 -q -o " + albedo_radius.string()).status, 0);
  EXPECT_NE(slurp(albedo_radius).find("exact"), std::string::npos);

  // fit profile and fit albedo: the exact model unless told otherwise.
  const auto measured = temp("skin1.csv");
  ASSERT_EQ(run("profile --material Skin1 -f csv -q -o " + measured.string()).status, 0);
  const auto fit = run("fit profile " + measured.string() + " -f json");
  ASSERT_EQ(fit.status, 0) << fit.err;
  EXPECT_EQ(nlohmann::json::parse(fit.out)["model"], "exact");
  const auto albedo = run("fit albedo --albedo 0.8,0.5,0.3 --distance 1,1,1 -f json");
  ASSERT_EQ(albedo.status, 0) << albedo.err;
  EXPECT_EQ(nlohmann::json::parse(albedo.out)["model"], "exact");
}

TEST(DefaultModelCli, FitAlbedoRecoversTheExactMediumItWasGiven) {
  // Skin1's exact totals and transport mean free paths, inverted: sigma_a and sigma_s' come back
  // (better-dipole, the former default, missed blue sigma_a by 23 %).
  const auto show = nlohmann::json::parse(run("materials show Skin1 -f json").out);
  std::string totals, distances;
  for (const auto& c : show["channels"]) {
    if (!totals.empty()) totals += ',', distances += ',';
    totals += nlohmann::json(c["surface_albedo"].get<double>()).dump();
    distances += nlohmann::json(c["transport_mfp"].get<double>()).dump();
  }
  const auto fit =
      run("fit albedo --albedo " + totals + " --distance " + distances + " --convention transport-mfp -f json");
  ASSERT_EQ(fit.status, 0) << fit.err;
  const auto doc = nlohmann::json::parse(fit.out);
  std::size_t c = 0;
  for (const auto& ch : doc["channels"]) {
    EXPECT_NEAR(ch["sigma_a"]["value"].get<double>() / show["channels"][c]["sigma_a"].get<double>(), 1.0, 1e-5)
        << ch.dump();
    ++c;
  }
  EXPECT_EQ(c, 3u);
}

TEST(DefaultModelCli, ValidityGoesToStderrWhateverTheFormatAndQuiet) {
  // better-dipole is invalid for Skin1's blue (its measured total error band exceeds 30 %): one line per
  // channel on stderr, with -q and JSON alike; the exact default has nothing to say.
  for (const std::string format : {"json", "csv", "table"}) {
    const auto r = run("profile --material Skin1 --model better-dipole --radii 1 -q -f " + format);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("bssrdf: validity: channel B, better-dipole: invalid ["), std::string::npos) << r.err;
    int lines_for_b = 0;
    for (std::size_t at = r.err.find("channel B,"); at != std::string::npos; at = r.err.find("channel B,", at + 1))
      ++lines_for_b;
    EXPECT_EQ(lines_for_b, 1) << r.err;
  }
  EXPECT_EQ(run("profile --material Skin1 --radii 1 -q -f json").err, "");
  const auto lut =
      run("lut --material Skin1 --model better-dipole --kind separable -q -o " + temp("kernel.json").string());
  EXPECT_NE(lut.err.find("channel B, better-dipole: invalid"), std::string::npos) << lut.err;
}

TEST(DefaultModelCli, MaterialsShowAndProfileAgreeOnValidity) {
  // One function decides (Model::validity of the default model): every warning and invalid verdict
  // `profile --material NAME` reports, `materials show NAME` reports too, channel by channel.
  for (const auto& m : bundled().all()) {
    const std::string name = "'" + m.name + "'";
    const auto profile = nlohmann::json::parse(run("profile --material " + name + " --radii 1 -q -f json").out);
    const auto show = nlohmann::json::parse(run("materials show " + name + " -f json").out);
    ASSERT_EQ(profile["channels"].size(), show["channels"].size()) << m.name;
    for (std::size_t c = 0; c < profile["channels"].size(); ++c) {
      std::set<std::string> from_profile, from_show;
      for (const auto& note : profile["channels"][c]["validity"])
        if (note["severity"] != "note") from_profile.insert(note["code"].get<std::string>());
      for (const auto& note : show["channels"][c]["validity"])
        if (note["severity"] != "note" && note["code"] != "object_size")
          from_show.insert(note["code"].get<std::string>());
      EXPECT_EQ(from_profile, from_show) << m.name << " channel " << c;
      EXPECT_EQ(show["channels"][c]["physical_model"], profile["model"]) << m.name;
    }
  }
}
