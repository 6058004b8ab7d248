// Rows where Prahl's iad may stop without a solution although ours converges: near the edges of
// the albedo a = mu_s / (mu_a + mu_s) in [0, 1], where iad searches. See iad_search_edge.cpp.
#pragma once

#include <string>

namespace bssrdf {

// Within this distance of a = 1 or a = 0 a converged row is marked (see iad_search_edge.cpp).
constexpr double kIadEdgeAlbedo = 0.01;

// The status of a converged, unconstrained row with these results: "converged", or "converged; "
// and why iad's search may stop on this row and why ours does not.
std::string converged_status(double mu_a, double mu_s_prime, double g, double chi2);

}  // namespace bssrdf
