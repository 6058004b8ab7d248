#include "bssrdf/models/fit_forms.hpp"

namespace bssrdf {

void prepare(FitForm& form, double eta) {
  if (auto* pbd = std::get_if<fit_forms::PhotonBeam>(&form.kind))
    pbd->samples = photon_beam_diffusion::samples_for_tolerance(0.9, 0.0, eta, 1e-6);
  if (auto* qd = std::get_if<fit_forms::Quantized>(&form.kind))
    qd->ratio = quantized_diffusion::ratio_for_tolerance(eta, 1e-3);
}

}  // namespace bssrdf
