// MCML input files (.mci, Wang & Jacques, MCML 1.2.2), so biomedical-optics users can bring their
// cases unchanged. Units as MCML: cm and 1/cm in the file; converted to mm here.
//
//   1.0                     # file version
//   1                       # number of runs
//   out.mco  A              # output file name, A(SCII) or B(inary) -- kept, not written
//   1000000                 # number of photons
//   0.01   0.002            # dz, dr [cm]
//   100    500    1         # number of dz, dr, da bins
//   1                       # number of layers
//   1.0                     # n above
//   1.4  1.0  100.0  0.9  10.0     # n, mua [1/cm], mus [1/cm], g, d [cm] per layer
//   1.0                     # n below
//
// '#' starts a comment; blank lines are skipped; each record is one line. Errors are FileError
// with the file and line.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "bssrdf/layers.hpp"

namespace bssrdf {

struct MciRun {
  std::string output_file;  // as given; informational
  char output_format = 'A';
  std::uint64_t photons = 0;
  double dz = 0, dr = 0;  // mm
  int nz = 0, nr = 0, na = 0;
  LayerStack stack;  // one channel named "mcml"; mm, 1/mm
  int line = 0;      // line of the run's first record
};

struct MciFile {
  double version = 1.0;
  std::vector<MciRun> runs;
};

MciFile read_mci(const std::filesystem::path& path);
MciFile parse_mci(const std::string& text, const std::string& name);

}  // namespace bssrdf
