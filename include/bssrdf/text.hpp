// Small text helpers for names typed by users: case folding and the distance behind "did you mean".
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace bssrdf {

// ASCII lower case (names of models, units, materials, options).
std::string lower(std::string_view text);
// Levenshtein distance: insertions, deletions and substitutions, one each.
std::size_t edit_distance(const std::string& a, const std::string& b);

}  // namespace bssrdf
