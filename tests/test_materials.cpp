// The bundled database and the loader's errors.
#include <gtest/gtest.h>

#include <unistd.h>
#include <array>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "bssrdf/derived_quantities.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/io/renderer_export.hpp"
#include "bssrdf/materials.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_choice.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/models/exact.hpp"
#include "cli_runner.hpp"
#include "json_schema_subset.hpp"
#include "reference_data.hpp"

using namespace bssrdf;

namespace {
std::filesystem::path write_temp(const std::string& name, const std::string& text) {
  const auto path = test_cli::temp(name);  // this process's scratch directory, removed at exit
  std::ofstream(path) << text;
  return path;
}

std::string load_error(const std::string& text) {
  try {
    MaterialDatabase::load(write_temp("m.json", text));
  } catch (const FileError& e) {
    return e.what();
  }
  return "";
}

const char* kHeader = R"({"format": "bssrdf-materials", "version": 1, "source": "test", "citation": "c",
  "unit": "mm", "channels": ["R", "G", "B"], "materials": [)";
}  // namespace

TEST(Materials, BundledJensenTableMatchesTheReference) {
  const auto db = MaterialDatabase::load(default_materials_dir());
  std::vector<const Material*> jensen;
  for (const auto& m : db.all())
    if (m.source == "jensen2001") jensen.push_back(&m);
  ASSERT_EQ(jensen.size(), 12u);
  // Every value against measured_media.tsv (the TSV stores sigma_s' as sigma_s with g = 0).
  std::ifstream in(std::string(BSSRDF_TEST_DATA) + "/measured_media.tsv");
  std::string line;
  int compared = 0;
  while (std::getline(in, line)) {
    if (line.rfind("jensen2001\t", 0) != 0) continue;
    std::istringstream f(line);
    std::string source, name;
    std::getline(f, source, '\t');
    std::getline(f, name, '\t');
    double eta, s[3], a[3];
    f >> eta >> s[0] >> s[1] >> s[2] >> a[0] >> a[1] >> a[2];
    const auto& m = db.find(name);
    EXPECT_DOUBLE_EQ(m.medium.eta, eta) << name;
    for (int c = 0; c < 3; ++c) {
      EXPECT_DOUBLE_EQ(m.medium.sigma_s[c], s[c]) << name;
      EXPECT_DOUBLE_EQ(m.medium.sigma_a[c], a[c]) << name;
      EXPECT_EQ(m.medium.g[c], 0.0);
    }
    EXPECT_TRUE(m.reduced_scattering_only);
    EXPECT_FALSE(m.citation.empty());
    ++compared;
  }
  EXPECT_EQ(compared, 12);
}

TEST(Materials, LookupIsCaseInsensitiveAndSuggestsCloseNames) {
  const auto db = MaterialDatabase::load(default_materials_dir());
  EXPECT_EQ(db.find("SKIN1").name, "Skin1");
  EXPECT_EQ(db.find("wholemilk").name, "Wholemilk");
  try {
    db.find("skim milk");
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("Skimmilk"), std::string::npos) << e.what();
  }
  try {
    db.find("Marbel");
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("Marble"), std::string::npos) << e.what();
  }
}

TEST(Materials, MalformedJsonNamesFileAndLine) {
  const std::string e = load_error(std::string(kHeader) + "\n{\"name\": \"A\",,}\n]}");
  EXPECT_NE(e.find("m.json:3:"), std::string::npos) << e;
  EXPECT_NE(e.find("malformed JSON"), std::string::npos) << e;
}

TEST(Materials, InvalidValuesNameTheField) {
  std::string e = load_error(std::string(kHeader) +
                             R"({"name": "A", "eta": 1.3, "sigma_a": [0.1, -2, 0.1], "sigma_s": [1, 1, 1]}]})");
  EXPECT_NE(e.find("$.materials[0] (A): sigma_a[G] = -2"), std::string::npos) << e;
  e = load_error(std::string(kHeader) + R"({"name": "A", "eta": 1.3, "sigma_a": [0.1, 0.1], "sigma_s": [1, 1, 1]}]})");
  EXPECT_NE(e.find("sigma_a: 2 values given"), std::string::npos) << e;
  e = load_error(std::string(kHeader) + R"({"name": "A", "sigma_a": [0.1, 0.1, 0.1], "sigma_s": [1, 1, 1]}]})");
  EXPECT_NE(e.find("missing required field 'eta'"), std::string::npos) << e;
  e = load_error(std::string(kHeader) +
                 R"({"name": "A", "eta": 1.3, "sigma_a": [0.1, 0.1, 0.1], "sigma_s": [1, 1, 1], "g": [0, 1.5, 0]}]})");
  EXPECT_NE(e.find("g[G] = 1.5: accepted range is -1 < g < 1"), std::string::npos) << e;
  e = load_error(
      std::string(kHeader) +
      R"({"name": "A", "eta": 1.3, "sigma_a": [0.1, 0.1, 0.1], "sigma_s": [1, 1, 1], "sigma_s_prime": [1, 1, 1]}]})");
  EXPECT_NE(e.find("exactly one of"), std::string::npos) << e;
  e = load_error(std::string(kHeader) + R"({"name": "A", "eta": 1.3, "sigma_a": [0.1, 0.1, 0.1], "sigma_s": [1, 1, 1]},
                                            {"name": "a", "eta": 1.3, "sigma_a": [0.1, 0.1, 0.1], "sigma_s": [1, 1, 1]}]})");
  EXPECT_NE(e.find("already defined"), std::string::npos) << e;
  EXPECT_NE(load_error("").find("malformed JSON"), std::string::npos);
  EXPECT_NE(load_error(R"({"format": "other"})").find("$.format"), std::string::npos);
}

TEST(Materials, UnitsAreConvertedToPerMillimetre) {
  const auto path =
      write_temp("cm.json", R"({"format": "bssrdf-materials", "version": 1, "source": "t", "citation": "c",
    "unit": "cm", "channels": ["x"], "materials": [{"name": "A", "eta": 1.4, "sigma_a": [1], "sigma_s": [100], "g": [0.9]}]})");
  const auto db = MaterialDatabase::load(path);
  EXPECT_DOUBLE_EQ(db.find("a").medium.sigma_a[0], 0.1);
  EXPECT_DOUBLE_EQ(db.find("a").medium.sigma_s[0], 10.0);
  EXPECT_DOUBLE_EQ(db.find("a").medium.g[0], 0.9);
}

TEST(Materials, BundledNarasimhanTableMatchesTheReference) {
  const auto db = MaterialDatabase::load(default_materials_dir());
  EXPECT_EQ(db.all().size(), 47u);  // 12 + 35: every row loads
  std::ifstream in(std::string(BSSRDF_TEST_DATA) + "/measured_media.tsv");
  std::string line;
  int compared = 0;
  while (std::getline(in, line)) {
    if (line.rfind("narasimhan2006\t", 0) != 0) continue;
    std::istringstream f(line);
    std::string source, name;
    std::getline(f, source, '\t');
    std::getline(f, name, '\t');
    double eta, s[3], a[3], g[3];
    f >> eta >> s[0] >> s[1] >> s[2] >> a[0] >> a[1] >> a[2] >> g[0] >> g[1] >> g[2];
    const auto& m = db.find(name);
    EXPECT_EQ(m.source, "narasimhan2006");
    EXPECT_DOUBLE_EQ(m.medium.eta, eta) << name;
    for (int c = 0; c < 3; ++c) {
      EXPECT_DOUBLE_EQ(m.medium.sigma_s[c], s[c]) << name;
      EXPECT_DOUBLE_EQ(m.medium.sigma_a[c], a[c]) << name;
      EXPECT_DOUBLE_EQ(m.medium.g[c], g[c]) << name;
      if (s[c] == 0) {
        EXPECT_EQ(g[c], 0.0) << name;
      }  // the TSV's convention
    }
    EXPECT_FALSE(m.reduced_scattering_only);
    ++compared;
  }
  EXPECT_EQ(compared, 35);
}

namespace {
test_schema::json read_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  return test_schema::json::parse(in);
}
}  // namespace

TEST(MaterialsSchema, IsValidJsonAndDescribesEveryBundledFile) {
  const auto dir = default_materials_dir();
  const auto schema = read_json(dir / "schema.json");  // throws if not JSON
  EXPECT_EQ(schema["$schema"], "https://json-schema.org/draft/2020-12/schema");
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".json" || entry.path().filename() == "schema.json") continue;
    EXPECT_EQ(test_schema::validate(schema, read_json(entry.path())), "") << entry.path();
    ++files;
  }
  EXPECT_EQ(files, 2);
}

// Every constraint the schema states, broken once: the schema rejects it and so does the loader,
// with a message naming the field. (Channel counts and sigma_a + sigma_s > 0, which JSON Schema
// cannot state, are covered by InvalidValuesNameTheField.)
TEST(MaterialsSchema, LoaderRejectsWhatTheSchemaRejects) {
  const auto schema = read_json(default_materials_dir() / "schema.json");
  const std::string good_entry =
      R"({"name": "A", "eta": 1.3, "sigma_a": [0.1, 0.1, 0.1], "sigma_s": [1, 1, 1], "g": [0, 0, 0]})";
  const auto file = [&](const std::string& top, const std::string& entry) {
    return "{" + top + R"("format": "bssrdf-materials", "version": 1, "source": "test", "citation": "c", "unit": "mm",
      "channels": ["R", "G", "B"], "materials": [)" +
           entry + "]}";
  };
  ASSERT_EQ(test_schema::validate(schema, test_schema::json::parse(file("", good_entry))), "");
  ASSERT_EQ(load_error(file("", good_entry)), "");
  struct Case {
    std::string text, message;
  };
  const std::vector<Case> cases = {
      {file(R"("extra": 1, )", good_entry), "$.extra: unknown field"},
      {file("", R"({"name": "A", "eta": 1.3, "sigma_a": [0.1, 0.1, 0.1], "sigma_s_prim": [1, 1, 1]})"),
       "sigma_s_prim: unknown field"},
      {file("", R"({"name": "", "eta": 1.3, "sigma_a": [0.1, 0.1, 0.1], "sigma_s": [1, 1, 1]})"),
       "$.materials[0].name: expected a non-empty string"},
      {file("", R"({"name": "A", "eta": 0, "sigma_a": [0.1, 0.1, 0.1], "sigma_s": [1, 1, 1]})"), "(A): eta = 0"},
      {file("", R"({"name": "A", "eta": "1.3", "sigma_a": [0.1, 0.1, 0.1], "sigma_s": [1, 1, 1]})"),
       "(A).eta: expected a number"},
      {file("", R"({"name": "A", "eta": 1.3, "sigma_a": [0.1, 0.1, 0.1], "sigma_s": [1, -1, 1]})"),
       "(A): sigma_s[G] = -1"},
      {file("", R"({"name": "A", "eta": 1.3, "sigma_a": [0.1, 0.1, 0.1], "sigma_s_prime": [1, 1, -1]})"),
       "(A): sigma_s[B] = -1"},
      {file("", R"({"name": "A", "eta": 1.3, "sigma_a": [0.1, 0.1, 0.1], "sigma_s": [1, 1, 1], "g": [-1, 0, 0]})"),
       "g[R] = -1"},
      {file("", R"({"name": "A", "eta": 1.3, "sigma_a": [0.1, 0.1, 0.1], "sigma_s": [1, 1, 1], "g": [0, 0, 1]})"),
       "g[B] = 1"},
      {file("", R"({"name": "A", "eta": 1.3, "sigma_a": [0.1, 0.1, 0.1]})"), "exactly one of"},
      {file("", R"({"name": "A", "eta": 1.3, "sigma_a": [0.1, 0.1, 0.1], "sigma_s_prime": [1, 1, 1], "g": [0, 0, 0]})"),
       "(A).g: 'g' cannot be given"},
      {file("", R"({"eta": 1.3, "sigma_a": [0.1, 0.1, 0.1], "sigma_s": [1, 1, 1]})"), "missing required field 'name'"},
      {file("", R"({"name": "A", "eta": 1.3, "sigma_a": [0.1, "x", 0.1], "sigma_s": [1, 1, 1]})"),
       "sigma_a[1]: expected a number"},
      {file("", R"({"name": "A", "eta": 1.3, "sigma_a": [0.1, 0.1, 0.1], "sigma_s": [1, 1, 1], "notes": 3})"),
       "(A).notes: expected a string"},
      {file("", "") + "", "$.materials: expected a non-empty array"},
      {R"({"format": "bssrdf-materials", "version": 2, "source": "t", "citation": "c", "unit": "mm", "channels": ["R"], "materials": []})",
       "$.version: only version 1"},
      {R"({"format": "other", "version": 1, "source": "t", "citation": "c", "unit": "mm", "channels": ["R"], "materials": []})",
       "$.format"},
      {R"({"format": "bssrdf-materials", "version": 1, "source": "", "citation": "c", "unit": "mm", "channels": ["R"], "materials": []})",
       "$.source: expected a non-empty string"},
      {R"({"format": "bssrdf-materials", "version": 1, "source": "t", "unit": "mm", "channels": ["R"], "materials": []})",
       "missing required field 'citation'"},
      {R"({"format": "bssrdf-materials", "version": 1, "source": "t", "citation": "c", "unit": "MM", "channels": ["R"], "materials": []})",
       "$.unit: 'MM' is not one of"},
      {R"({"format": "bssrdf-materials", "version": 1, "source": "t", "citation": "c", "unit": "mm", "channels": [], "materials": []})",
       "$.channels: expected a non-empty array"},
      {R"({"format": "bssrdf-materials", "version": 1, "source": "t", "citation": "c", "unit": "mm", "channels": ["R", "R"], "materials": []})",
       "$.channels[1]: 'R' is repeated"},
      {R"({"format": "bssrdf-materials", "version": 1, "source": "t", "citation": "c", "unit": "mm", "channels": ["R", ""], "materials": []})",
       "$.channels[1]: expected a non-empty string"},
  };
  for (const auto& c : cases) {
    const auto doc = test_schema::json::parse(c.text);
    EXPECT_NE(test_schema::validate(schema, doc), "") << "the schema accepts: " << c.text;
    const std::string e = load_error(c.text);
    EXPECT_NE(e.find(c.message), std::string::npos) << "expected '" << c.message << "', got: " << e;
    EXPECT_NE(e.find("m.json"), std::string::npos) << e;
  }
}

TEST(Materials, UserDatabaseAddsToTheBundledOneAndClashesAreErrors) {
  const auto user = write_temp(
      "user.json", std::string(kHeader) +
                       R"({"name": "My Wax", "eta": 1.45, "sigma_a": [0.01, 0.02, 0.03], "sigma_s": [2, 2, 2]}]})");
  const auto db = MaterialDatabase::load_with_user(user);
  EXPECT_EQ(db.all().size(), 48u);
  EXPECT_EQ(db.find("my wax").medium.eta, 1.45);
  EXPECT_EQ(db.find("Skin1").source, "jensen2001");
  const auto clash = write_temp(
      "clash.json",
      std::string(kHeader) + R"({"name": "skin1", "eta": 1.3, "sigma_a": [0.01, 0.02, 0.03], "sigma_s": [2, 2, 2]}]})");
  try {
    MaterialDatabase::load_with_user(clash);
    FAIL();
  } catch (const FileError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("clash.json"), std::string::npos) << what;
    EXPECT_NE(what.find("'skin1' is already defined in"), std::string::npos) << what;
    EXPECT_NE(what.find("jensen2001.json"), std::string::npos) << what;
  }
}

TEST(DerivedQuantities, MatchHandComputedValues) {
  const auto db = MaterialDatabase::load(default_materials_dir());
  // Skin1 R (Jensen 2001): sigma_a 0.032, sigma_s' 0.74 1/mm, g = 0.
  auto q = derive_quantities(db.find("Skin1").medium);
  const auto& r = q.channels[0];
  EXPECT_DOUBLE_EQ(r.albedo_prime, 0.74 / 0.772);
  EXPECT_DOUBLE_EQ(r.mfp, 1 / 0.772);
  EXPECT_DOUBLE_EQ(r.transport_mfp, 1 / 0.772);
  EXPECT_NEAR(r.diffuse_mfp, 1 / std::sqrt(3 * 0.032 * 0.772), 1e-12);
  EXPECT_EQ(q.physical_model, "exact");  // every channel inside the exact model's domain
  for (const auto& c : q.channels) EXPECT_TRUE(c.valid()) << c.name << ": " << describe(c.validity.front());
  // Lowfat Milk B (Narasimhan 2006): sigma_s 17.9572, sigma_a 0.0115, g 0.859.
  q = derive_quantities(db.find("Lowfat Milk").medium);
  const auto& b = q.channels[2];
  const double sp = 17.9572 * (1 - 0.859), tp = 0.0115 + sp;
  EXPECT_NEAR(b.mfp, 1 / (0.0115 + 17.9572), 1e-15);
  EXPECT_NEAR(b.sigma_s_prime, sp, 1e-12);
  EXPECT_NEAR(b.albedo_prime, sp / tp, 1e-12);
  EXPECT_NEAR(b.transport_mfp, 1 / tp, 1e-12);
  EXPECT_NEAR(b.diffuse_mfp, 1 / std::sqrt(3 * 0.0115 * tp), 1e-9);
  EXPECT_NEAR(b.albedo, 17.9572 / (17.9572 + 0.0115), 1e-15);
  // Burley's d sits near the physical profile's scale and the fit reports its quality.
  for (const auto& c : q.channels) {
    EXPECT_GT(c.burley_d, 0);
    EXPECT_GT(c.burley_error, 0);
    EXPECT_GT(c.surface_albedo, 0);
    EXPECT_LT(c.surface_albedo, 1);
  }
}

// Burley's d is fitted to the exact profile inside its domain: against that profile it is at least
// as close as the d fitted to pbd (what the database gave before), and channels outside the
// domain fall back to pbd, named per channel.
TEST(DerivedQuantities, BurleyDIsFittedToTheExactProfileInsideItsDomain) {
  const auto db = MaterialDatabase::load(default_materials_dir());
  const auto exact = make_model("exact");
  // sqrt(int r (burley - exact)^2 dr / int r exact^2 dr) by the trapezoid rule in r.
  const auto error_vs_exact = [&](const Reduced<double>& m, double A, double d) {
    const auto r = burley_fit_radii_mm(m, 400);
    double num = 0, den = 0;
    for (std::size_t i = 0; i + 1 < r.size(); ++i) {
      const auto term = [&](double x) {
        const double R = exact->reflectance(m, x);
        const double B = A * (std::exp(-x / d) + std::exp(-x / (3 * d))) / (8 * std::numbers::pi * d * x);
        return std::array{x * (B - R) * (B - R), x * R * R};
      };
      const auto a = term(r[i]), b = term(r[i + 1]);
      num += 0.5 * (a[0] + b[0]) * (r[i + 1] - r[i]);
      den += 0.5 * (a[1] + b[1]) * (r[i + 1] - r[i]);
    }
    return std::sqrt(num / den);
  };
  DerivationOptions pbd;
  pbd.physical_model = "pbd";
  for (const char* name : {"Skin1", "Marble", "Wholemilk", "Ketchup"}) {
    const auto& medium = db.find(name).medium;
    const auto q = derive_quantities(medium), old = derive_quantities(medium, pbd);
    EXPECT_EQ(q.physical_model, "exact") << name;
    EXPECT_EQ(old.physical_model, "pbd") << name;
    for (std::size_t c = 0; c < medium.channels(); ++c) {
      const auto m = medium.reduced(c);
      const auto& now = q.channels[c];
      EXPECT_EQ(now.physical_model, "exact");
      const double e_exact = error_vs_exact(m, now.surface_albedo, now.burley_d);
      const double e_pbd = error_vs_exact(m, now.surface_albedo, old.channels[c].burley_d);
      EXPECT_LE(e_exact, e_pbd * 1.001) << name << " " << now.name;
      EXPECT_NEAR(e_exact, now.burley_error, 0.1 * now.burley_error) << name << " " << now.name;
      std::printf("[ measured ] %s %s: Burley d %.4g mm (exact) vs %.4g mm (pbd); L2 vs exact %.3f vs %.3f\n", name,
                  now.name.c_str(), now.burley_d, old.channels[c].burley_d, e_exact, e_pbd);
    }
  }
  // Spectralon (alpha' 1) and Coke (alpha' below 0.001, and 0) are inside the exact domain now; every
  // channel takes the registry's default (default_model), and a medium outside names what it took.
  EXPECT_EQ(derive_quantities(db.find("Spectralon").medium).physical_model, "exact");
  EXPECT_EQ(derive_quantities(db.find("Coke").medium).physical_model, "exact");
  for (const auto& m : db.all()) {
    const auto q = derive_quantities(m.medium);
    for (std::size_t c = 0; c < m.medium.channels(); ++c)
      EXPECT_EQ(q.channels[c].physical_model, default_model(m.medium.reduced(c)).name) << m.name;
  }
  Medium mixed = db.find("Skin1").medium;
  mixed.g = {0.0, -0.3, 0.0};  // G outside the exact domain (g < 0)
  const auto q = derive_quantities(mixed);
  const std::string other = default_model(mixed.reduced(1)).name;
  EXPECT_EQ(q.physical_model, "exact (" + other + " for G)");
  EXPECT_NE(q.channels[1].model_choice.find("g = -0.3"), std::string::npos) << q.channels[1].model_choice;
}

namespace {
bool has(const ValidityReport& report, const std::string& code) {
  for (const auto& note : report)
    if (note.code == code) return true;
  return false;
}
}  // namespace

TEST(DerivedQuantities, ValidityIsTheProfileModelsWithTheObjectSize) {
  const auto db = MaterialDatabase::load(default_materials_dir());
  // Sprite: alpha' ~ 0.003 (the exact profile is valid there: no diffusion approximation) and a
  // transport mfp of ~500 mm, which the object size flags.
  auto q = derive_quantities(db.find("Sprite").medium);
  for (const auto& c : q.channels) {
    EXPECT_TRUE(c.valid()) << c.name;
    EXPECT_TRUE(has(c.validity, "object_size")) << c.name;
  }
  // The same medium under a diffusion model carries that model's own verdict, as `profile` prints it.
  DerivationOptions dipole;
  dipole.physical_model = "dipole";
  for (const auto& c : derive_quantities(db.find("Sprite").medium, dipole).channels) EXPECT_FALSE(c.valid()) << c.name;
  // Merlot G and B do not scatter at all: no Burley fit, and a note says so.
  q = derive_quantities(db.find("Merlot").medium);
  EXPECT_TRUE(std::isnan(q.channels[1].burley_d));
  EXPECT_TRUE(has(q.channels[1].validity, "no_scattering"));
  // The object size is the user's: Skin1 R (ell = 1.3 mm) is not diffuse in a 1 mm object.
  DerivationOptions small;
  small.object_size_mm = 1;
  q = derive_quantities(db.find("Skin1").medium, small);
  EXPECT_TRUE(has(q.channels[0].validity, "object_size"));
  EXPECT_FALSE(has(q.channels[2].validity, "object_size"));  // ell = 0.67 mm
  // How many of the database's channels the default profile serves without a warning at 10 mm.
  int clean = 0, total = 0;
  for (const auto& m : db.all())
    for (const auto& c : derive_quantities(m.medium).channels) clean += worst(c.validity) == Severity::note, ++total;
  std::printf("no warning in %d of %d channels (object size 10 mm)\n", clean, total);
  EXPECT_LT(clean, total);
}

TEST(Materials, JsonExportRoundTripsThroughEveryUnit) {
  const auto db = MaterialDatabase::load(default_materials_dir());
  std::vector<ExportEntry> entries;
  for (const auto& m : db.all()) entries.push_back({m, {}});
  for (const auto unit : {LengthUnit::micrometre, LengthUnit::millimetre, LengthUnit::centimetre, LengthUnit::metre}) {
    EXPECT_DOUBLE_EQ(from_mm(to_mm(1.2345, unit), unit), 1.2345);
    EXPECT_DOUBLE_EQ(coefficient_from_per_mm(coefficient_to_per_mm(0.37, unit), unit), 0.37);
    // Mixed sources and channel-compatible: one file with every material.
    const auto path = write_temp("export-" + std::string(symbol(unit)) + ".json",
                                 export_materials(RendererTarget::json, entries, unit));
    const auto back = MaterialDatabase::load(path);
    ASSERT_EQ(back.all().size(), db.all().size());
    for (std::size_t i = 0; i < db.all().size(); ++i) {
      const auto& a = db.all()[i];
      const auto& b = back.all()[i];
      EXPECT_EQ(a.name, b.name);
      EXPECT_EQ(b.unit, unit);
      EXPECT_EQ(a.reduced_scattering_only, b.reduced_scattering_only);
      EXPECT_EQ(a.medium.eta, b.medium.eta);
      for (std::size_t c = 0; c < 3; ++c) {
        EXPECT_NEAR(b.medium.sigma_a[c], a.medium.sigma_a[c], 1e-15 * a.medium.sigma_a[c]) << a.name;
        EXPECT_NEAR(b.medium.sigma_s[c], a.medium.sigma_s[c], 1e-15 * a.medium.sigma_s[c]) << a.name;
        EXPECT_EQ(b.medium.g[c], a.medium.g[c]);
      }
    }
  }
}
