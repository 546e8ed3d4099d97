#pragma once
// A LatticeVolume as an executor's frame (gpu/lattice_executor.h), for the
// gpu layer's tests: its records at `nodes`, their Planck tables, and the
// sun's irradiance there when `sun_scene` has a sun.
#include <vector>

#include "obscura/gpu/lattice_executor.h"
#include "obscura/render/lattice/lattice_volume.h"
#include "obscura/render/spectral_nodes.h"
#include "obscura/scene/scene.h"

namespace obscura::testing {

inline FrameLattice frame_of(const LatticeVolume& volume, const std::vector<SpectralNode>& nodes,
                             const Scene* sun_scene) {
  FrameLattice f;
  f.view = volume.view();
  f.stride = volume.stride();
  for (std::size_t u = 0; u < nodes.size(); ++u) {
    f.records.push_back(volume.records(static_cast<int>(u)));
    f.planck.push_back(nodes[u].planck_table->view());
    f.sun_irradiance.push_back(sun_scene && sun_scene->sun.enabled
                                   ? sun_scene->sun.irradiance(nodes[u].wavelength_um)
                                   : 0.0);
  }
  return f;
}

}  // namespace obscura::testing
