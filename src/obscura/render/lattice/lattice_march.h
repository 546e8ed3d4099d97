#pragma once
// The camera march over a LatticeVolume (lattice_volume.h): the march over its
// view (lattice_view_march.h, the code a CUDA device runs too) for every node
// of a band along one ray. The volume must hold the medium
// (LatticeVolume::has_medium). The result equals the medium's own march
// (Medium::march_cells with the same cells) up to float rounding of the
// records: the cells, points and quadrature are the same.
#include <array>
#include <cstdint>

#include "obscura/core/ray.h"
#include "obscura/render/lattice/lattice_view_march.h"
#include "obscura/render/lattice/lattice_volume.h"
#include "obscura/render/spectral_nodes.h"

namespace obscura {

// Adds to radiance[j] the radiance emitted and scattered towards the ray's
// origin over [0, t_max] and multiplies transmittance[j] by the line's e^{−τ},
// for the `nodes` spectral nodes whose records are volume.records(record[j]);
// a source that keeps forward scattering multiplies attenuation[j] too
// (march_lattice_ray). `volume.stride()` must be Stride. Returns the cells
// visited.
template <int Stride, class Source>
std::uint64_t march_lattice(const LatticeVolume& volume, const int* record, int nodes,
                            const Ray& ray, double t_max, const Source& source, double* radiance,
                            double* transmittance, double* attenuation = nullptr) {
  std::array<const float*, kMaxSpectralNodes> records;
  for (int j = 0; j < nodes; ++j) records[j] = volume.records(record[j]);
  // A band of one node (a laser line, the benchmark's LWIR band) takes the
  // instance a device thread runs, whose state stays in registers: 535
  // instructions per voxel step against 677 (callgrind, docs/performance.md).
  if (nodes == 1)
    return march_lattice_view<Stride, 1>(volume.view(), records.data(), 1, ray, t_max, source,
                                         radiance, transmittance, attenuation);
  return march_lattice_view<Stride, kMaxSpectralNodes>(volume.view(), records.data(), nodes, ray,
                                                       t_max, source, radiance, transmittance,
                                                       attenuation);
}

}  // namespace obscura
