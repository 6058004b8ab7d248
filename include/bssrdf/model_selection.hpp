// Which profile model a request means, and the line for people saying why: shared by the command
// line (`--model NAME|auto`, `--accuracy`) and the Python module (`model=`, `accuracy=`), so both
// choose and explain the same model in the same words.
//
//   const auto chosen = select_model("auto", 0.05, skin);   // the cheapest within 5 %
//   auto model = make_model(chosen.name);
//   if (!chosen.note.empty()) std::cout << chosen.note;     // "auto: pbd, the cheapest measured within 5 % ..."
//
// The decisions themselves live in model_choice.hpp (default_model, choose_model); this file only
// maps a request onto them and words the outcome.
#pragma once

#include <optional>
#include <string>

#include "bssrdf/medium.hpp"
#include "bssrdf/model_choice.hpp"
#include "bssrdf/model_registry.hpp"

namespace bssrdf {

// The accuracy `--model auto` takes when none is given, and the accepted range of one.
inline constexpr double kDefaultModelAccuracy = 0.1;
// Throws InvalidInput naming `field` unless 0 < accuracy < 10.
void check_model_accuracy(double accuracy, const std::string& field = "accuracy");

struct SelectedModel {
  std::string name;
  std::string note;  // why this model: auto's choice, or why the default is not exact; else empty
};

// `name` empty: the registry's default (default_model), noted when it is not `exact`; "auto": the cheapest
// measured within `accuracy` (kDefaultModelAccuracy when nullopt) in every channel (choose_model), with the
// cheaper ones it passed over; any other name as given. An accuracy without "auto" is an InvalidInput
// naming `accuracy_field` and `model_field` (the caller's names: "--accuracy", "--model").
SelectedModel select_model(const std::string& name, std::optional<double> accuracy, const Medium& medium,
                           const std::string& accuracy_field = "accuracy", const std::string& model_field = "model");

// The line `select_model` gives for an auto choice made for `accuracy`.
std::string describe_choice(const ModelChoice& choice, double accuracy);

// What `bssrdf models` says of where a model holds: its measured total-error bands against
// adding-doubling, or a reference model's band against fresh Monte Carlo.
std::string measured_domain(const ModelEntry& entry);

}  // namespace bssrdf
