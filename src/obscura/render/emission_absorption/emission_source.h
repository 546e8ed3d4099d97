#pragma once
// Emission–absorption's source for the lattice march
// (render/lattice/lattice_view_march.h): σt = σa + σs and the emissivity
// σa B(T) from an interpolated record, B from each node's Planck table. Plain
// data, so that a CUDA device runs it too (docs/gpu.md).
#include "obscura/core/host_device.h"
#include "obscura/core/planck_table.h"
#include "obscura/render/lattice/lattice_view.h"

namespace obscura {

struct EmissionSource {
  const PlanckTableView* planck;  // per node j of the march

  OBSCURA_HOST_DEVICE void point(int j, const float* v, double& sigma_t, double& emissivity) const {
    const double sigma_a = v[record::kSigmaA];
    sigma_t = sigma_a + v[record::kSigmaS];
    emissivity = sigma_a != 0.0 ? sigma_a * planck[j](v[record::kTemperature]) : 0.0;
  }
};

}  // namespace obscura
