// reference --mci writes each run's MCML output file (.mco), read back here the way MCML's own
// reader (mcmlio.c / CONV: skip blank and '#' lines to the next label, then scan numbers) does.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>

#include "cli_runner.hpp"

using namespace bssrdf;

namespace {
// MCML's FindDataLine: the next line that is not blank and does not start with '#'.
std::string find_data_line(std::istream& in) {
  std::string line;
  while (std::getline(in, line)) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first != std::string::npos && line[first] != '#') return line;
  }
  ADD_FAILURE() << "unexpected end of .mco";
  return "";
}

struct Mco {
  std::string version, name;
  long photons = 0;
  double dz = 0, dr = 0;
  int nz = 0, nr = 0, na = 0, layers = 0;
  double Rsp = 0, Rd = 0, A = 0, Tt = 0;
  std::vector<double> A_l, A_z, Rd_r, Rd_a, Tt_r, Tt_a, A_rz, Rd_ra, Tt_ra;
};

std::vector<double> scan(std::istream& in, const std::string& label, std::size_t count) {
  const std::string line = find_data_line(in);
  EXPECT_EQ(line.rfind(label, 0), 0u) << "expected " << label << ", got: " << line;
  std::vector<double> out(count);
  for (auto& v : out) in >> v;
  EXPECT_TRUE(in.good()) << label;
  return out;
}

Mco read_mco(const std::filesystem::path& path) {
  std::ifstream in(path);
  Mco m;
  std::istringstream(find_data_line(in)) >> m.version;
  EXPECT_EQ(find_data_line(in).rfind("InParm", 0), 0u);
  std::string format;
  std::istringstream(find_data_line(in)) >> m.name >> format;
  std::istringstream(find_data_line(in)) >> m.photons;
  std::istringstream(find_data_line(in)) >> m.dz >> m.dr;
  std::istringstream(find_data_line(in)) >> m.nz >> m.nr >> m.na;
  std::istringstream(find_data_line(in)) >> m.layers;
  for (int i = 0; i < m.layers + 2; ++i) find_data_line(in);  // n above, the layers, n below
  EXPECT_EQ(find_data_line(in).rfind("RAT", 0), 0u);
  std::istringstream(find_data_line(in)) >> m.Rsp;
  std::istringstream(find_data_line(in)) >> m.Rd;
  std::istringstream(find_data_line(in)) >> m.A;
  std::istringstream(find_data_line(in)) >> m.Tt;
  m.A_l = scan(in, "A_l", m.layers);
  m.A_z = scan(in, "A_z", m.nz);
  m.Rd_r = scan(in, "Rd_r", m.nr);
  m.Rd_a = scan(in, "Rd_a", m.na);
  m.Tt_r = scan(in, "Tt_r", m.nr);
  m.Tt_a = scan(in, "Tt_a", m.na);
  m.A_rz = scan(in, "A_rz", static_cast<std::size_t>(m.nr) * m.nz);
  m.Rd_ra = scan(in, "Rd_ra", static_cast<std::size_t>(m.nr) * m.na);
  m.Tt_ra = scan(in, "Tt_ra", static_cast<std::size_t>(m.nr) * m.na);
  return m;
}
}  // namespace

TEST(Mco, WrittenForEachRunAndReadBackAsMcmlReadsIt) {
  // Two runs: a two-layer 0.1 cm slab (transmission) and a thick slab; nr bins of 0.01 cm.
  const auto mci = test_cli::temp("two.mci");
  std::ofstream(mci) << "1.0\n2\n"
                        "slab.mco A\n20000\n0.01 0.01\n10 20 1\n2\n1.0\n1.37 1 100 0.9 0.05\n1.37 1 10 0 0.05\n1.0\n"
                        "thick.mco A\n20000\n0.02 0.005\n25 40 1\n1\n1.0\n1.4 1 100 0.9 10\n1.0\n";
  const auto json_out = test_cli::temp("runs.json");
  const auto r = test_cli::run("reference --mci " + mci.string() + " --mco-dir " + test_cli::scratch().string() +
                               " --format json -o " + json_out.string() + " -q");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto runs = nlohmann::json::parse(test_cli::slurp(json_out))["runs"];
  const char* names[] = {"slab.mco", "thick.mco"};
  for (int k = 0; k < 2; ++k) {
    SCOPED_TRACE(names[k]);
    const auto m = read_mco(test_cli::temp(names[k]));
    const auto& ch = runs[k]["channels"][0];
    EXPECT_EQ(m.version, "A1");
    EXPECT_EQ(m.name, names[k]);
    EXPECT_EQ(m.photons, 20000);
    EXPECT_EQ(m.na, 1);
    EXPECT_EQ(m.nz, k == 0 ? 10 : 25);
    EXPECT_EQ(m.nr, k == 0 ? 20 : 40);
    EXPECT_DOUBLE_EQ(m.dr, k == 0 ? 0.01 : 0.005);
    EXPECT_DOUBLE_EQ(m.dz, k == 0 ? 0.01 : 0.02);
    EXPECT_EQ(m.layers, k == 0 ? 2 : 1);
    // RAT equals the run's own totals (6 significant digits).
    EXPECT_NEAR(m.Rd, ch["diffuse_reflectance"]["value"].get<double>(), 1e-6);
    EXPECT_NEAR(m.Tt, ch["total_transmittance"]["value"].get<double>(), 1e-6);
    EXPECT_NEAR(m.A, ch["absorbed"]["value"].get<double>(), 1e-6);
    EXPECT_NEAR(m.Rsp, ch["specular_reflectance"].get<double>(), 1e-6);
    // MCML's identities: the arrays integrate to the totals (%12.4E: 5 digits).
    double rd = 0, tt = 0, a_z = 0, a_l = 0;
    for (int i = 0; i < m.nr; ++i) {
      const double area = 2 * std::numbers::pi * (i + 0.5) * m.dr * m.dr;
      rd += m.Rd_r[i] * area;
      tt += m.Tt_r[i] * area;
    }
    for (double v : m.A_z) a_z += v * m.dz;
    for (double v : m.A_l) a_l += v;
    EXPECT_NEAR(rd / m.Rd, 1.0, 2e-4);
    if (k == 0) {
      EXPECT_NEAR(tt / m.Tt, 1.0, 2e-4);
    }
    EXPECT_NEAR(a_z / m.A, 1.0, 2e-4);
    EXPECT_NEAR(a_l / m.A, 1.0, 2e-4);
    const double da = std::numbers::pi / 2;
    EXPECT_NEAR(m.Rd_a[0] * 2 * std::numbers::pi * da * std::sin(da / 2) / m.Rd, 1.0, 2e-4);
    // Rd_r is the run's R(r) in 1/cm^2 (the JSON is in cm too), bin for bin below the last.
    for (int i = 0; i + 1 < m.nr; ++i)
      EXPECT_NEAR(m.Rd_r[i], ch["reflectance"][i].get<double>(), 1e-4 * ch["reflectance"][i].get<double>() + 1e-12)
          << i;
    // A_rz is not tallied: zeros, and the file says so.
    for (double v : m.A_rz) EXPECT_EQ(v, 0.0);
  }
  EXPECT_NE(test_cli::slurp(test_cli::temp("slab.mco")).find("# A_rz: not tallied"), std::string::npos);
  // The two layers: A_l splits the absorption between them, the first (mus 100/cm) taking more.
  const auto slab = read_mco(test_cli::temp("slab.mco"));
  EXPECT_GT(slab.A_l[0], slab.A_l[1]);
  EXPECT_GT(slab.A_l[1], 0.0);
}
