// The layer-stack file: a plain JSON description of planar layers, shared by the Monte Carlo
// reference (`bssrdf reference --layers FILE`) and layered models.
//
//   {
//     "format": "bssrdf-layers", "version": 1,
//     "unit": "mm",                        // length unit of thickness and 1/unit of coefficients
//     "ambient_above": 1.0,                // refractive index above (light comes from here) [1]
//     "ambient_below": 1.0,                // refractive index below the last layer [1]
//     "channels": ["R", "G", "B"],         // optional: default R,G,B for three, c0, c1, ... else
//     "layers": [                          // top to bottom
//       { "name": "epidermis", "thickness": 0.1, "n": 1.4,
//         "sigma_a": [..], "sigma_s": [..], "g": [..] },     // one value, or one per channel
//       { "name": "dermis", "thickness": null, "eta": 1.4, ... }  // null/absent: semi-infinite
//     ]
//   }
//
// "n" (or its synonym "eta") is the layer's absolute index; default 1.4 (soft tissue; 1 would make a
// scattering layer index-matched to air). "g" defaults to 0.
// Unknown keys are errors (they are usually typos). Errors are FileError with the file and the
// line of the offending value: "skin.json:7: layers[0].sigma_a[G] = -1: accepted range is ...".
#pragma once

#include <filesystem>
#include <string>

#include "bssrdf/layers.hpp"
#include "bssrdf/units.hpp"

namespace bssrdf {

struct LayersFile {
  LayerStack stack;                          // mm, 1/mm
  LengthUnit unit = LengthUnit::millimetre;  // the unit the file uses (outputs default to it)
};

LayersFile read_layers_json(const std::filesystem::path& path);
// From text; `name` is used in error messages.
LayersFile parse_layers_json(const std::string& text, const std::string& name);

}  // namespace bssrdf

namespace bssrdf {
// The file's text for `stack` (lengths in mm, coefficients in 1/mm, channel names kept): what read_layers_json reads
// back to the same stack.
std::string layers_json(const LayerStack& stack);
}  // namespace bssrdf
