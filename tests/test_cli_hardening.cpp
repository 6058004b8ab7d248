// The defects of the hardening audit (issue 15), each reproduced end to end against the binary:
// crashes, destroyed special files, internal errors, silent wrong values, hangs and raw control
// bytes. Every bad input must give exit status 2, one line naming the field, the value and the
// accepted range, and no output file.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <chrono>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

using namespace bssrdf;
using test_cli::count_lines;
using test_cli::run;
using test_cli::temp;
using json = nlohmann::json;

namespace {

std::filesystem::path write(const std::string& name, const std::string& text) {
  const auto path = temp(name);
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// Exit 2, one line on stderr, containing every fragment, no output file.
void expect_refused(const test_cli::Run& r, std::initializer_list<std::string> fragments) {
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  for (const auto& f : fragments) EXPECT_NE(r.err.find(f), std::string::npos) << "missing '" << f << "' in: " << r.err;
}

std::string profile_csv(const std::string& value, const std::string& stderr_value) {
  std::string text = "radius_mm,R" + std::string(stderr_value.empty() ? "" : ",R_stderr") + "\n";
  for (int i = 1; i <= 8; ++i) {
    const std::string v = i == 4 ? value : std::to_string(std::exp(-i));
    text += std::to_string(0.1 * i) + "," + v + (stderr_value.empty() ? "" : "," + (i == 4 ? stderr_value : "0.001")) +
            "\n";
  }
  return text;
}

}  // namespace

// Crash (SIGSEGV in the covariance) on a value or stderr of 1e308; inf chi^2 on a stderr of 1e-308.
TEST(Hardening, FitProfileRefusesValuesNoProfileCanHold) {
  expect_refused(run("fit profile " + write("v.csv", profile_csv("1e308", "0.001")).string()),
                 {"v.csv:5: R = 1e+308", "accepted range is 0 to 1e+30"});
  expect_refused(run("fit profile " + write("s.csv", profile_csv("0.01", "1e308")).string()),
                 {"R_stderr = 1e+308", "accepted range"});
  expect_refused(run("fit profile " + write("t.csv", profile_csv("0.01", "1e-308")).string()),
                 {"R_stderr = 1e-308", "1e-30 to 1e+30"});
  expect_refused(run("fit profile " + write("n.csv", profile_csv("1e308", "")).string()), {"R = 1e+308"});
}

// -1 wrapped to 2^64 - 1 for unsigned options (a crash in the report); no upper bound on photons.
TEST(Hardening, CountsAreSignedAndRangeChecked) {
  expect_refused(run("reference --sigma-a 1 --sigma-s 1 -n -1"), {"--photons = '-1'", "1 to 10000000000"});
  expect_refused(run("reference --sigma-a 1 --sigma-s 1 -n 2e10"), {"--photons = '2e10'"});
  expect_refused(run("reference --sigma-a 1 --sigma-s 1 -n 1.5"), {"--photons = '1.5'", "a whole number"});
  expect_refused(run("reference --sigma-a 1 --sigma-s 1 --bins -1"), {"--bins = '-1'", "2 to 10000000"});
  expect_refused(run("reference --sigma-a 1 --sigma-s 1 --seed -1"), {"--seed = '-1'"});
  expect_refused(run("reference --sigma-a 1 --sigma-s 1 --threads 99999"), {"--threads = '99999'", "0 to 4096"});
  // CLI11 read '' as 0 for a double: a roulette threshold of 0 traced 1000 photons for 9 s (1e6: hours).
  expect_refused(run("reference --sigma-a 0.1 --sigma-s 1 --roulette-threshold ''"),
                 {"--roulette-threshold = ''", "a finite number"});
  expect_refused(run("reference --sigma-a 0.1 --sigma-s 1 --roulette-threshold 0"),
                 {"--roulette-threshold = 0", "1e-12 <= threshold < 1"});
  expect_refused(run("lut --kind radial --reference --sigma-a 1 --sigma-s 1 --photons -1 -o " + temp("t.exr").string()),
                 {"--photons = '-1'"});
  expect_refused(run("profile --material skin1 --samples -5"), {"--samples = '-5'", "2 to 1000000"});
  expect_refused(run("fit gaussians --material skin1 -n 99"), {"--count = '99'", "1 to 32"});
  EXPECT_FALSE(std::filesystem::exists(temp("t.exr")));
  // The help states the range.
  const auto help = run("reference --help");
  EXPECT_NE(help.out.find("(1 to 10000000000)"), std::string::npos) << help.out;
  // "1e4" is a whole number: accepted.
  const auto ok = run("reference --sigma-a 1 --sigma-s 9 -n 1e4 --bins 10 -f json");
  ASSERT_EQ(ok.status, 0) << ok.err;
  EXPECT_EQ(json::parse(ok.out)["photons"].get<double>(), 1e4);
}

// -o renamed its temporary file over the target: a device, FIFO or symlink was replaced by a file.
TEST(Hardening, OutputNeverReplacesSpecialFilesOrLinks) {
  // A symlink: the file it names gets the content, the link stays a link.
  const auto target = write("target.json", "old");
  const auto link = temp("link.json");
  std::filesystem::create_symlink(target, link);
  ASSERT_EQ(run("profile --material skin1 -q -o " + link.string()).status, 0);
  EXPECT_TRUE(std::filesystem::is_symlink(link));
  EXPECT_EQ(json::parse(test_cli::slurp(target))["material"]["name"], "Skin1");

  // A FIFO is written into, not replaced.
  const auto fifo = temp("fifo");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const auto received = temp("received.json");
  const std::string command = "cat " + fifo.string() + " > " + received.string() + " & " + std::string(BSSRDF_CLI) +
                              " profile --material skin1 -q -f json -o " + fifo.string() + "; s=$?; wait; exit $s";
  EXPECT_EQ(std::system(command.c_str()), 0);
  EXPECT_TRUE(std::filesystem::is_fifo(fifo));
  EXPECT_EQ(json::parse(test_cli::slurp(received))["material"]["name"], "Skin1");

  // A character device like /dev/null (a private node, so a regression cannot break the system's).
  const auto device = temp("null");
  if (::mknod(device.c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0) {
    EXPECT_EQ(run("profile --material skin1 -q -f json -o " + device.string()).status, 0);
    EXPECT_TRUE(std::filesystem::is_character_file(device));
  }

  expect_refused(run("profile --material skin1 -o ''"), {"-o = ''", "a file name"});
  expect_refused(run("lut --material skin1 -o ''"), {"-o = ''"});
  expect_refused(run("profile --material skin1 -q -o " + temp("").string()), {"directory"});
}

// JSON numbers beyond a double and wrong types gave "[json.exception...]" with exit 1.
TEST(Hardening, JsonOverflowAndWrongTypesNameFileAndLine) {
  const auto db = write("db.json",
                        "{\"format\": \"bssrdf-materials\", \"version\": 1, \"source\": \"x\", \"citation\": \"x\",\n"
                        "\"unit\": \"mm\", \"channels\": [\"R\"],\n\"materials\": [{\"name\": \"A\", \"eta\": 1.3,\n"
                        "\"sigma_a\": [1e400], \"sigma_s_prime\": [1]}]}\n");
  expect_refused(run("profile --material A --db " + db.string()), {db.string() + ":4:", "1e400"});
  const auto digits = std::string(400, '9');
  const auto layers =
      write("layers.json", "{\"format\": \"bssrdf-layers\", \"version\": 1,\n\"layers\": [{\"thickness\": " + digits +
                               ", \"n\": 1.4, \"sigma_a\": 1, \"sigma_s\": 1}]}\n");
  expect_refused(run("reference --layers " + layers.string()), {layers.string() + ":2:"});
  const auto fit =
      write("fit.json", "{\"source\": \"fit\", \"shared\": {\"eta\": {\"value\": \"1.3\"}}, \"channels\": [{}]}");
  expect_refused(run("materials import " + fit.string() + " --name X -o " + temp("m.json").string()), {fit.string()});
  const auto overflow = write("fit2.json", "{\"source\": \"fit\", \"channels\": [{\"sigma_a\": {\"value\": 1e999}}]}");
  expect_refused(run("materials import " + overflow.string() + " --name X -o " + temp("m.json").string()),
                 {overflow.string() + ":1:", "1e999"});
  expect_refused(run("materials import " + temp("").string() + " --name X -o " + temp("m.json").string()),
                 {"directory"});
  EXPECT_FALSE(std::filesystem::exists(temp("m.json")));
}

// An imported sigma_a of 1e308 was accepted, then the file failed to load ("--r-min = nan"), and
// errors named an internal temporary file.
TEST(Hardening, ImportRefusesWhatCannotLoadAndNamesTheUsersFile) {
  const auto fit =
      write("fit.json",
            "{\"source\": \"fit\", \"shared\": {\"eta\": {\"value\": 1.3}}, \"channels\": [{\"name\": \"R\", "
            "\"sigma_a\": {\"value\": 1e308, \"unit\": \"1/mm\"}, \"sigma_s_prime\": {\"value\": 1}}]}");
  const auto out = temp("mine.json");
  const auto r = run("materials import " + fit.string() + " --name X -o " + out.string());
  expect_refused(r, {out.string(), "sigma_a[R] = 1e+308"});
  EXPECT_EQ(r.err.find(".bssrdf-import-check"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(out));
}

// .mci bin counts wrapped through static_cast<int> (3e9 -> 2 bins); dz = 4.9e-324 gave null output.
TEST(Hardening, MciCountsAndLengthsAreBounded) {
  const auto mci = [](const std::string& grid, const std::string& sizes) {
    return "1.0\n1\nout.mco A\n100\n" + grid + "\n" + sizes + "\n1\n1.0\n1.4 1 10 0.9 1e8\n1.0\n";
  };
  const auto a = write("a.mci", mci("0.01 0.01", "10 3e9 1"));
  expect_refused(run("reference --mci " + a.string()),
                 {a.string() + ":6:", "number of dr bins = 3e9", "1 to 10000000"});
  const auto b = write("b.mci", mci("0.01 0.01", "10 2e9 1"));
  expect_refused(run("reference --mci " + b.string()), {b.string() + ":6:"});
  const auto c = write("c.mci", mci("4.9e-324 0.01", "10 10 1"));
  expect_refused(run("reference --mci " + c.string()), {c.string() + ":5:", "dz = 4.9e-324"});
  const auto d = write("d.mci", "1.0\n1\nout.mco A\n100\n0.01 0.01\n10 10 1\n1\n1e-308\n1.4 1 10 0.9 1\n1.0\n");
  expect_refused(run("reference --mci " + d.string()), {d.string() + ":8:", "n above = 1e-308", "0.2 to 5"});
}

// Absurd indices made Monte Carlo run for minutes on 300 photons.
TEST(Hardening, RefractiveIndicesHavePhysicalBounds) {
  expect_refused(run("reference --sigma-a 1e-9 --sigma-s 1 --eta 100 -n 300"), {"--eta = 100", "0.2 to 5"});
  expect_refused(run("profile --sigma-a 1e308 --sigma-s 1"), {"--sigma-a[c0] = 1e+308", "at most 1e+06"});
  const auto layers = write("n.json",
                            "{\"format\": \"bssrdf-layers\", \"version\": 1, \"ambient_above\": 1e-9,\n"
                            "\"layers\": [{\"thickness\": 1, \"n\": 1.4, \"sigma_a\": 1, \"sigma_s\": 1}]}\n");
  const auto r = run("reference --layers " + layers.string() + " -n 300");
  expect_refused(r, {"ambient_above"});
}

// A layers file nested 100,000 deep took > 150 s and echoed the whole value.
TEST(Hardening, DeepJsonIsRefusedQuicklyAndBriefly) {
  const auto deep =
      write("deep.json", "{\"format\": \"bssrdf-layers\", \"version\": 1, \"layers\": " + std::string(100000, '[') +
                             std::string(100000, ']') + "}");
  const auto start = std::chrono::steady_clock::now();
  const auto r = run("reference --layers " + deep.string());
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
  expect_refused(r, {deep.string() + ":1:", "nested deeper than 64"});
  EXPECT_LT(r.err.size(), 300u);
  const auto wide =
      write("wide.json", "{\"format\": \"bssrdf-layers\", \"version\": 1, \"layers\": [{\"thickness\": 1, \"n\": " +
                             std::string("[") + std::string(20000, '1') + "], \"sigma_a\": 1, \"sigma_s\": 1}]}");
  const auto w = run("reference --layers " + wide.string());
  EXPECT_EQ(w.status, 2);
  EXPECT_LT(w.err.size(), 300u) << "the value is echoed in full";
}

// A CR inside a CSV field reached the terminal raw.
TEST(Hardening, ControlBytesAreEscapedInMessages) {
  const auto csv = write("cr.csv", "radius_mm,R\n0.1,1\n0.2,0\r5\n0.3,1\n0.4,1\n");
  const auto r = run("fit profile " + csv.string());
  expect_refused(r, {"\\x0d"});
  EXPECT_EQ(r.err.find('\r'), std::string::npos);
}

// The tool's own Monte Carlo CSV was fitted with its bin-edge columns as channels (sigma_a = 7.2e10).
TEST(Hardening, FitProfileReadsMonteCarloCsv) {
  const auto mc = temp("mc.csv");
  ASSERT_EQ(
      run("reference --sigma-a 0.05 --sigma-s 5 --eta 1.0 -n 200000 --bins 40 --r-max 8 -q -f csv -o " + mc.string())
          .status,
      0);
  const auto r = run("fit profile " + mc.string() + " --eta 1.0 -f json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto doc = json::parse(r.out);
  ASSERT_EQ(doc["channels"].size(), 1u);
  EXPECT_EQ(doc["channels"][0]["name"], "c0");
  // The default (exact) model averaged over the file's bins recovers the medium (measured: sigma_a
  // 0.0504 +- 0.0005, sigma_s' 5.001 +- 0.02; R at the bins' centres missed sigma_a by a factor 2).
  EXPECT_EQ(doc["model"], "exact");
  EXPECT_NEAR(doc["channels"][0]["sigma_a"]["value"].get<double>() / 0.05, 1.0, 0.03);
  EXPECT_NEAR(doc["channels"][0]["sigma_s_prime"]["value"].get<double>() / 5, 1.0, 0.02);
}

// "negative transmittance" (exit 1) from the multipole on valid input; the README promises values >= 0.
TEST(Hardening, MultipoleFarTailIsNeverAnInternalError) {
  const auto r = run("profile --sigma-a 1e-9 --sigma-s 1 --eta 1.3 --thickness 100 --radii 1,10000 -f json");
  EXPECT_TRUE(r.status == 0 || r.status == 2) << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  const auto doc = r.status == 0 ? json::parse(r.out) : json();
  if (r.status == 0) {
    for (const auto& ch : doc["channels"])
      for (const char* key : {"reflectance", "transmittance"})
        for (const auto& v : ch[key]) EXPECT_GE(v.get<double>(), 0.0) << key;
  }
}

// Burley's R(0) was written as null in a numeric array: r = 0 is refused where R(r) diverges.
TEST(Hardening, NumericArraysHoldNumbersOnly) {
  expect_refused(run("profile --material skin1 --model burley --radii 0,0.5,1 -f json"),
                 {"--radii = 0", "> 0 for burley"});
  const auto r = run("profile --material skin1 --model burley --radii 0.001,0.5,1 -f json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto doc = json::parse(r.out);
  for (const auto& ch : doc["channels"])
    for (const auto& v : ch["reflectance"]) EXPECT_TRUE(v.is_number()) << ch["reflectance"].dump();
}

// Lengths beyond any object: --thickness 1e308 was reported as "r_max = 0", --r-max 1e308 as a NaN radius.
TEST(Hardening, LengthsAreBoundedAndNamedAsTyped) {
  expect_refused(run("profile --sigma-a 0.1 --sigma-s 1 --thickness 1e308"), {"--thickness = 1e+308", "at most 1e+06"});
  expect_refused(run("profile --sigma-a 0.1 --sigma-s 1 --r-max 1e308"), {"--r-max = 1e+308"});
  expect_refused(run("profile --sigma-a 0.1 --sigma-s 1 --radii 1,1e300"), {"--radii = 1e+300"});
  expect_refused(run("transmission --sigma-a 0.1 --sigma-s 1 --d-max 1e308"), {"--d-max = 1e+308"});
  expect_refused(run("reference --sigma-a 0.1 --sigma-s 1 --r-max 1e308 -n 100"), {"--r-max = 1e+308"});
  // Bins of zero width gave R(r) = null in the JSON.
  expect_refused(run("reference --sigma-a 0.1 --sigma-s 1 --r-max 4.9e-324 -n 100"),
                 {"--r-max = 4.9e-324", "1e-9 mm per bin"});
  const auto layers = write("thick.json",
                            "{\"format\": \"bssrdf-layers\", \"version\": 1,\n"
                            "\"layers\": [{\"thickness\": 1e300, \"n\": 1.4, \"sigma_a\": 1, \"sigma_s\": 1}]}\n");
  expect_refused(run("reference --layers " + layers.string() + " -n 100"), {"thickness", "at most 1e6 mm"});
}

// Fits say how far the model itself is from radiative transfer where that exceeds 1 %.
TEST(Hardening, FitWarnsAboutTheModelsOwnError) {
  const auto data = temp("skin.csv");
  ASSERT_EQ(run("profile --material skin1 --model dipole -f csv -q -o " + data.string()).status, 0);
  const auto r = run("fit profile " + data.string() + " --model dipole -f json");
  ASSERT_EQ(r.status, 0) << r.err;
  bool said = false;
  const auto doc = json::parse(r.out);
  for (const auto& w : doc["warnings"])
    said |= w.get<std::string>().find("statistical only; dipole itself differs") != std::string::npos;
  EXPECT_TRUE(said) << r.out.substr(0, 2000);
}

// --size went through sscanf("%u"): "-1x10" wrapped to 4 billion albedos (a hang), 1e5 x 1e5 ran out of memory (exit
// 1).
TEST(Hardening, TableSizesAreSignedAndBounded) {
  const auto out = temp("t.exr");
  expect_refused(run("lut --kind albedo-radius --layout family --size -1x10 -o " + out.string()),
                 {"--size = '-1x10'", "4 to 2048"});
  expect_refused(run("lut --kind albedo-radius --layout family --size 100000x100000 -o " + out.string()),
                 {"--size = '100000x100000'"});
  expect_refused(run("lut --kind preintegrated --material skin1 --size 0x-5 -o " + out.string()),
                 {"--size = '0x-5'", "2 to 8192"});
  EXPECT_FALSE(std::filesystem::exists(out));
}
