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
// Without leading and trailing blanks and tabs (a list item typed as "0.1, 0.2").
std::string trim(const std::string& text);

}  // namespace bssrdf
