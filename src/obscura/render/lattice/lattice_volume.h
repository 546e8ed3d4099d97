#pragma once
// A voxel grid and, optionally, the light in it, at the nodes of a NodeLattice
// laid on the grid at its own voxel size, per spectral node of a frame, in the
// layout the lattice march reads (lattice_march.h): one record of stride()
// floats per node, its channels (record::, lattice_view.h)
//   [σa, σs, T, σs g, τ_sun, V_sun, c_00, c_1−1, c_10, …]
// (1/m, 1/m, K, 1/m, optical depth, 0…1, then the radiance cache's spherical-
// harmonic coefficients). σa, σs and σs g are interpolated linearly in
// wavelength between the grid's samples (SpectralNode::lerp) when the volume
// is made, so that a point of the march interpolates one record per corner
// rather than every sample's channels. The radiance cache fills the light
// channels (τ_sun on); emission–absorption reads the first three.
//
// Exact: at the grid's voxel size a lattice's nodes are the voxel centres plus
// one rim node each side, and a rim node holds the edge voxel's values, so the
// trilinear interpolation of the records is the grid's own clamped
// reconstruction (medium/grid_medium.h) everywhere inside the grid's box,
// domain(). σs g interpolated and divided by the interpolated σs is the grid's
// σs-weighted g. Nodes of blocks the lattice does not hold read as the zero
// record, zero_slot(), as the medium is zero there.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "obscura/core/bbox.h"
#include "obscura/medium/medium.h"
#include "obscura/medium/tracking.h"
#include "obscura/render/lattice/lattice_view.h"
#include "obscura/render/lattice/node_lattice.h"

namespace obscura {

class LatticeVolume {
 public:
  // The grid `medium` consists of when `lattice` is laid on it at its voxel
  // size (NodeLattice at voxel_m 0, not periodic); null otherwise, when the
  // lattice march would not be exact.
  static const VoxelGrid* aligned_grid(const Medium& medium, const NodeLattice& lattice);

  // Bytes the records of `nodes` spectral nodes at `stride` floats would take.
  static double bytes_needed(const NodeLattice& lattice, int nodes, int stride);

  // Records on `lattice` for `lerps.size()` spectral nodes, `stride` floats
  // each (≥ record::kMediumStride), all zero; with a `grid` (which the
  // lattice must be laid on: aligned_grid) its values at `lerps` fill the
  // medium channels. Checks the memory limit first (core/memory_limit.h),
  // naming `field`.
  LatticeVolume(const NodeLattice& lattice, const std::vector<SpectralLerp>& lerps, int stride,
                const VoxelGrid* grid, int threads, const std::string& field);

  const NodeLattice& lattice() const { return *lattice_; }
  // Whether the medium channels hold a grid (else only what the owner wrote).
  bool has_medium() const { return has_medium_; }
  int stride() const { return stride_; }
  int node_count() const { return static_cast<int>(records_.size()); }
  // The record standing for every node of an absent block: all zero.
  std::size_t zero_slot() const { return lattice_->slot_count(); }
  const float* records(int node) const { return records_[static_cast<std::size_t>(node)].data(); }
  float* record(int node, std::size_t slot) {
    return records_[static_cast<std::size_t>(node)].data() +
           slot * static_cast<std::size_t>(stride_);
  }
  // Per slot (and the zero slot): whether σa or σs is non-zero there at any
  // of the grid's samples. A cell none of whose corners is occupied is clear.
  const std::uint8_t* occupied() const { return occupied_.data(); }
  // The grid's box in lattice coordinates (NodeLattice::to_lattice): where
  // the medium is; the march clips its rays to it.
  const BBox3& domain() const { return domain_; }
  std::size_t memory_bytes() const;
  // The march's view of this volume and its lattice (valid while both live).
  LatticeView view() const;

 private:
  const NodeLattice* lattice_;
  int stride_;
  bool has_medium_ = false;
  std::vector<std::vector<float>> records_;
  std::vector<std::uint8_t> occupied_;
  BBox3 domain_;
};

// A lattice laid on a cloud that is one voxel grid, at its voxel size, and
// that grid's records at `lerps` (the medium channels, `stride` floats per
// record): what emission–absorption marches (and the GPU). Both null when the
// medium is not one grid that such a lattice reproduces exactly
// (LatticeVolume::aligned_grid).
struct GridRecords {
  std::unique_ptr<NodeLattice> lattice;
  std::unique_ptr<LatticeVolume> volume;
};
GridRecords grid_records(const Medium& medium, const std::vector<SpectralLerp>& lerps, int stride,
                         int threads);

}  // namespace obscura
