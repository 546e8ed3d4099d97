#pragma once
// A dense regular voxel grid of radiative properties (docs/formats.md): for each of
// N spectral samples (wavelengths in µm) the absorption and scattering
// coefficients σa, σs (1/m) and the Henyey–Greenstein asymmetry g, plus one
// temperature (K) per voxel. This is "what the grid stores"; GridMedium is how
// the render layer samples it (docs/conventions.md §3).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "obscura/core/bbox.h"
#include "obscura/core/memory_limit.h"
#include "obscura/medium/grid_placement.h"

namespace obscura {

struct GridDims {
  int nx = 0, ny = 0, nz = 0;
  std::size_t count() const {
    return static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny) *
           static_cast<std::size_t>(nz);
  }
  bool operator==(const GridDims&) const = default;
};

class VoxelGrid {
 public:
  // Checks the dimensions (each > 0, product without overflow) and that the
  // storage fits in available memory before allocating; throws InputError
  // naming `source` (a file name or JSON path) otherwise. Values start at
  // σa = σs = g = 0 and T = 0 K.
  VoxelGrid(GridDims dims, GridPlacement placement, std::vector<double> wavelengths_um,
            const std::string& source = "");

  const GridDims& dims() const { return dims_; }
  const GridPlacement& placement() const { return placement_; }
  void set_placement(const GridPlacement& p) { placement_ = p; }
  const std::vector<double>& wavelengths_um() const { return wavelengths_um_; }
  int spectral_count() const { return static_cast<int>(wavelengths_um_.size()); }

  // Linear voxel index, x fastest.
  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(dims_.nx) *
               (static_cast<std::size_t>(j) + static_cast<std::size_t>(dims_.ny) * k);
  }

  // Channel arrays of dims().count() floats each.
  float* sigma_a(int sample) { return channel(sample); }
  float* sigma_s(int sample) { return channel(spectral_count() + sample); }
  float* g(int sample) { return channel(2 * spectral_count() + sample); }
  float* temperature() { return channel(3 * spectral_count()); }
  const float* sigma_a(int sample) const { return channel(sample); }
  const float* sigma_s(int sample) const { return channel(spectral_count() + sample); }
  const float* g(int sample) const { return channel(2 * spectral_count() + sample); }
  const float* temperature() const { return channel(3 * spectral_count()); }

  // Names of the channels as stored in keyframe files: sigma_a_000, sigma_s_000,
  // g_000, ..., temperature (docs/formats.md).
  std::string channel_name(int channel_index) const;
  int channel_count() const { return 3 * spectral_count() + 1; }
  float* channel(int c) { return data_.data() + static_cast<std::size_t>(c) * dims_.count(); }
  const float* channel(int c) const {
    return data_.data() + static_cast<std::size_t>(c) * dims_.count();
  }

  // Checks every value: coefficients finite and >= 0, g in (−1, 1), temperature
  // finite and >= 0. Throws InputError(source, "<channel> voxel (i,j,k)", ...).
  void validate(const std::string& source) const;

  // World-space axis-aligned box around the (possibly rotated) grid.
  BBox3 world_bounds() const;
  std::size_t memory_bytes() const { return data_.size() * sizeof(float); }

  // Bytes the grid would need; throws InputError if the dims are invalid,
  // overflow, or exceed the memory available on this machine.
  static std::size_t checked_storage_bytes(GridDims dims, int spectral_count,
                                           const std::string& source);

 private:
  GridDims dims_;
  GridPlacement placement_;
  std::vector<double> wavelengths_um_;
  std::vector<float> data_;
};

}  // namespace obscura
