// Instructions per exact profile build in each part of the domain, for callgrind, whose counts do
// not depend on the machine's load (wall times on a shared machine do):
//   for c in 0 1 2 3 4 5; do
//     valgrind --tool=callgrind --callgrind-out-file=/dev/null build/tools/bench/exact_build_instructions $c
//     valgrind --tool=callgrind --callgrind-out-file=/dev/null build/tools/bench/exact_build_instructions $c 0
//   done
// (the difference of the two "Collected" counts over the builds' number is one build's cost).
//   exact_build_instructions CASE [builds]   CASE 0 table, 1 alpha' > 0.9999, 2 g > 0.99, 3 eta near 2,
//                                            4 alpha' below the first node, 5 the same through the per-radius
//                                            single-scattering path (the previous one);
//                                            builds: 200 (20 for cases 4 and 5)
#include <cstdio>
#include <cstdlib>

#include "bssrdf/models/exact.hpp"

using namespace bssrdf;

volatile double sink;

int main(int argc, char** argv) {
  const int which = argc > 1 ? std::atoi(argv[1]) : 0;
  if (which < 0 || which > 5) {
    std::fprintf(stderr, "exact_build_instructions: CASE = %s: accepted range is 0 to 5\n", argv[1]);
    return 2;
  }
  const int n = argc > 2 ? std::atoi(argv[2]) : which >= 4 ? 20 : 200;
  const auto& table = bundled_exact_table();
  sink = ExactProfile(table, 0.5, 0.5, 1.3).total();  // the table's load, in both counts
  for (int k = 0; k < n; ++k) {
    const double u = (k + 1) / (n + 1.0);
    switch (which) {
      case 0:
        sink = ExactProfile(table, 0.2 + 0.7 * u, 0.5, 1.35).total();
        break;
      case 1:
        sink = ExactProfile(table, 1 - 9e-5 * u, 0.3, 1.35).total();
        break;
      case 2:
        sink = ExactProfile(table, 0.7, 0.99 + 9e-3 * u, 1.35).total();
        break;
      case 3:
        sink = ExactProfile(table, 0.7, 0.5, 2.0 - 0.02 * u).total();
        break;
      case 4:
        sink = ExactProfile(table, table.albedo_prime.front() * u, 0.5, 1.35).total();
        break;
      case 5:
        sink =
            ExactProfile(table, table.albedo_prime.front() * u, 0.5, 1.35, SingleScatteringRadii::per_radius).total();
        break;
    }
  }
  std::printf("%d builds\n", n);
  return 0;
}
