// The measured errors behind choose_model (model_choice.hpp), embedded so the tool needs no data
// file at run time: one row per Monte Carlo validation case.
#pragma once

#include <array>
#include <string_view>
#include <vector>

namespace bssrdf::detail {

inline constexpr std::size_t kCandidateModels = 9;

struct MeasuredError {
  double total;    // |relative error of the total reflectance|
  double profile;  // area-weighted relative L2 error of R(r)
};

struct MeasuredCase {
  double albedo_prime, eta, g;
  std::array<MeasuredError, kCandidateModels> error;  // in the order of kCandidateNames
};

extern const std::array<std::string_view, kCandidateModels> kCandidateNames;
extern const std::vector<MeasuredCase> kMeasuredCases;

}  // namespace bssrdf::detail
