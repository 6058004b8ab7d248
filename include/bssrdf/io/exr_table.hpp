// Lookup tables as OpenEXR images: one EXR channel per table channel (float32, or half on
// request), the table's metadata as typed header attributes (string, double, int), uncompressed so
// that the same inputs give the same bytes. Encoded in memory, so callers write the result
// atomically (io/atomic_file.hpp) and a failure never leaves a partial file.
#pragma once

#include <string>

#include "bssrdf/lut/lookup_table.hpp"

namespace bssrdf {

enum class ExrPixelType { float32, half };

std::string encode_exr(const LookupTable& table, ExrPixelType type = ExrPixelType::float32);

}  // namespace bssrdf
