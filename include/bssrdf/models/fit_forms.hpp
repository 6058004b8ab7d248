// The forward forms profile fits evaluate: R(r) at every radius of one channel, templated on the
// number type so that a fit can differentiate it (ceres::Jet in src/fit/profile_fit.cpp; this
// header includes no Ceres). The model registry (model_registry.hpp) names one form per model;
// a model without a templated form uses NumericForm and is differentiated numerically through its
// runtime Model::reflectance.
//
//   FitForm form = model_entry("pbd").fit_form;
//   prepare(form, eta);                 // discretisation as the runtime model's at this eta
//   evaluate(form, m, radii, out);      // T = double or ceres::Jet
#pragma once

#include <cstddef>
#include <type_traits>
#include <variant>
#include <vector>

#include "bssrdf/fresnel.hpp"
#include "bssrdf/models/better_dipole.hpp"
#include "bssrdf/models/dipole.hpp"
#include "bssrdf/models/photon_beam_diffusion.hpp"
#include "bssrdf/models/quantized_diffusion.hpp"
#include "bssrdf/reduced.hpp"
#include "bssrdf/single_scattering.hpp"

namespace bssrdf::fit_forms {

// No templated form: the fit differentiates Model::reflectance numerically.
struct Numeric {};

struct ClassicalDipole {
  template <class T>
  void operator()(const Reduced<T>& m, const std::vector<double>& radii, T* out) const {
    for (std::size_t i = 0; i < radii.size(); ++i) out[i] = classical_dipole::reflectance(m, T(radii[i]));
  }
};

struct BetterDipole {
  template <class T>
  void operator()(const Reduced<T>& m, const std::vector<double>& radii, T* out) const {
    const auto b = improved_boundary(m.eta);
    for (std::size_t i = 0; i < radii.size(); ++i) out[i] = better_dipole::reflectance(m, b, T(radii[i]));
  }
};

// Photon beam diffusion with its own single scattering, at the Gauss-Legendre order prepared.
struct PhotonBeam {
  int samples = 16;
  template <class T>
  void operator()(const Reduced<T>& m, const std::vector<double>& radii, T* out) const {
    const auto b = improved_boundary(m.eta);
    for (std::size_t i = 0; i < radii.size(); ++i)
      out[i] = photon_beam_diffusion::reflectance(m, b, T(radii[i]), samples);
  }
};

struct Quantized {
  double ratio = 1.1;
  template <class T>
  void operator()(const Reduced<T>& m, const std::vector<double>& radii, T* out) const {
    const auto mix = quantized_diffusion::mixture(m, improved_boundary(m.eta), ratio);
    for (std::size_t i = 0; i < radii.size(); ++i) out[i] = quantized_diffusion::reflectance(mix, T(radii[i]));
  }
};

}  // namespace bssrdf::fit_forms

namespace bssrdf {

struct FitForm {
  std::variant<fit_forms::Numeric, fit_forms::ClassicalDipole, fit_forms::BetterDipole, fit_forms::PhotonBeam,
               fit_forms::Quantized>
      kind;
  bool plus_single_scattering = false;  // the NAME+ss models: exact single scattering added (32 points)

  bool numeric() const { return std::holds_alternative<fit_forms::Numeric>(kind); }
};

// The discretisation the runtime model uses at this eta (pbd: 1e-6 at alpha' 0.9; quantized: 1e-3).
void prepare(FitForm& form, double eta);

// R(r_i) into out[i] (not for a Numeric form).
template <class T>
void evaluate(const FitForm& form, const Reduced<T>& m, const std::vector<double>& radii, T* out) {
  std::visit(
      [&](const auto& f) {
        if constexpr (!std::is_same_v<std::decay_t<decltype(f)>, fit_forms::Numeric>) f(m, radii, out);
      },
      form.kind);
  if (form.plus_single_scattering)
    for (std::size_t i = 0; i < radii.size(); ++i)
      if (radii[i] > 0) out[i] += single_scattering_reflectance(m, T(radii[i]), 32);
}

}  // namespace bssrdf
