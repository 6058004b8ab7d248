// The bundled database and the loader's errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "bssrdf/error.hpp"
#include "bssrdf/materials.hpp"
#include "reference_data.hpp"

using namespace bssrdf;

namespace {
std::filesystem::path write_temp(const std::string& name, const std::string& text) {
  // Per process: ctest runs test cases in parallel processes.
  const auto dir = std::filesystem::temp_directory_path() / ("bssrdf-materials-test-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
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
  e = load_error(std::string(kHeader) +
                 R"({"name": "A", "eta": 1.3, "sigma_a": [0.1, 0.1, 0.1], "sigma_s": [1, 1, 1], "sigma_s_prime": [1, 1, 1]}]})");
  EXPECT_NE(e.find("exactly one of"), std::string::npos) << e;
  e = load_error(std::string(kHeader) + R"({"name": "A", "eta": 1.3, "sigma_a": [0.1, 0.1, 0.1], "sigma_s": [1, 1, 1]},
                                            {"name": "a", "eta": 1.3, "sigma_a": [0.1, 0.1, 0.1], "sigma_s": [1, 1, 1]}]})");
  EXPECT_NE(e.find("already defined"), std::string::npos) << e;
  EXPECT_NE(load_error("").find("malformed JSON"), std::string::npos);
  EXPECT_NE(load_error(R"({"format": "other"})").find("$.format"), std::string::npos);
}

TEST(Materials, UnitsAreConvertedToPerMillimetre) {
  const auto path = write_temp("cm.json", R"({"format": "bssrdf-materials", "version": 1, "source": "t", "citation": "c",
    "unit": "cm", "channels": ["x"], "materials": [{"name": "A", "eta": 1.4, "sigma_a": [1], "sigma_s": [100], "g": [0.9]}]})");
  const auto db = MaterialDatabase::load(path);
  EXPECT_DOUBLE_EQ(db.find("a").medium.sigma_a[0], 0.1);
  EXPECT_DOUBLE_EQ(db.find("a").medium.sigma_s[0], 10.0);
  EXPECT_DOUBLE_EQ(db.find("a").medium.g[0], 0.9);
}
