#include "obscura/render/spectral_nodes.h"

#include <algorithm>

namespace obscura {

SpectralNodes::SpectralNodes(const BandQuadrature& quadrature,
                             const std::vector<double>& medium_wavelengths_um)
    : quadrature_(quadrature) {
  const auto& wl = quadrature.wavelengths_um();
  const auto& w = quadrature.weights();
  const auto& mw = medium_wavelengths_um;
  for (std::size_t i = 0; i < wl.size(); ++i) {
    SpectralNode n;
    n.wavelength_um = wl[i];
    n.weight_um = w[i];
    n.planck = PlanckAtWavelength(wl[i]);
    if (mw.size() <= 1 || wl[i] <= mw.front()) {
      n.sample0 = n.sample1 = 0;
    } else if (wl[i] >= mw.back()) {
      n.sample0 = n.sample1 = static_cast<int>(mw.size()) - 1;
    } else {
      const auto it = std::upper_bound(mw.begin(), mw.end(), wl[i]);
      n.sample1 = static_cast<int>(it - mw.begin());
      n.sample0 = n.sample1 - 1;
      n.frac = (wl[i] - mw[n.sample0]) / (mw[n.sample1] - mw[n.sample0]);
    }
    nodes_.push_back(n);
  }
}

}  // namespace obscura
