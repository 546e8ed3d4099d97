#pragma once
// The exact optical depth of the medium along a camera ray up to its first
// surface, per medium spectral sample: the line-of-sight transmittance
// e^{−τ(λ)} that the Monte Carlo methods report beside their radiance (the
// emission–absorption integrator finds it as it integrates).
#include <cmath>
#include <vector>

#include "obscura/render/integrator.h"

namespace obscura {

class LineOfSight {
 public:
  // τ per medium sample from the camera to ray.t_end(); no allocation once
  // the buffer has its size. Without a medium, τ = 0.
  void compute(const Medium* medium, const CameraRay& camera) {
    tau_.assign(medium ? medium->wavelengths_um().size() : 1, 0.0);
    if (medium) medium->add_optical_depth(camera.ray, 0.0, camera.t_end(), tau_.data());
  }
  double transmittance(const SpectralNode& node) const {
    return std::exp(-node.lerp()(tau_.data()));
  }

 private:
  std::vector<double> tau_;
};

}  // namespace obscura
