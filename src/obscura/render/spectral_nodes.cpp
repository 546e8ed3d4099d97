#include "obscura/render/spectral_nodes.h"

namespace obscura {

SpectralNodes::SpectralNodes(const BandQuadrature& quadrature,
                             const std::vector<double>& medium_wavelengths_um)
    : quadrature_(quadrature) {
  const auto& wl = quadrature.wavelengths_um();
  const auto& w = quadrature.weights();
  for (std::size_t i = 0; i < wl.size(); ++i) {
    SpectralNode n;
    n.wavelength_um = wl[i];
    n.weight_um = w[i];
    n.planck = PlanckAtWavelength(wl[i]);
    n.planck_table = std::make_shared<const PlanckTable>(wl[i]);
    const SpectralLerp at = SpectralLerp::at(medium_wavelengths_um, wl[i]);
    n.sample0 = at.sample0;
    n.sample1 = at.sample1;
    n.frac = at.frac;
    nodes_.push_back(n);
  }
}

}  // namespace obscura
