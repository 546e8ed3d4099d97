#pragma once
// The wavelengths at which a band is rendered: the nodes of its quadrature,
// each with its quadrature weight, its Planck constants, and where it falls
// between the medium's spectral samples. Medium coefficients are interpolated
// linearly in wavelength between samples and held constant beyond the first
// and last sample (a grey medium has one sample).
#include <memory>
#include <vector>

#include "obscura/core/band.h"
#include "obscura/core/planck.h"
#include "obscura/core/planck_table.h"
#include "obscura/medium/tracking.h"

namespace obscura {

// Largest number of spectral nodes per band the integrators handle: per-ray
// arrays are this long, on the stack.
inline constexpr int kMaxSpectralNodes = 64;

struct SpectralNode {
  double wavelength_um = 0;
  double weight_um = 0;  // quadrature weight × response, µm
  PlanckAtWavelength planck;
  // The same tabulated in T (inner loops: the cell marcher).
  std::shared_ptr<const PlanckTable> planck_table;
  int sample0 = 0, sample1 = 0;  // bracketing medium samples
  double frac = 0;               // weight of sample1
  SpectralLerp lerp() const { return {sample0, sample1, frac}; }
};

class SpectralNodes {
 public:
  SpectralNodes(const BandQuadrature& quadrature, const std::vector<double>& medium_wavelengths_um);

  const std::vector<SpectralNode>& nodes() const { return nodes_; }
  std::size_t size() const { return nodes_.size(); }
  const BandQuadrature& quadrature() const { return quadrature_; }

 private:
  BandQuadrature quadrature_;
  std::vector<SpectralNode> nodes_;
};

}  // namespace obscura
