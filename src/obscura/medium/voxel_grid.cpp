#include "obscura/medium/voxel_grid.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "obscura/core/error.h"
#include "obscura/core/memory_limit.h"

namespace obscura {

std::size_t VoxelGrid::checked_storage_bytes(GridDims dims, int spectral_count,
                                             const std::string& source) {
  if (dims.nx <= 0 || dims.ny <= 0 || dims.nz <= 0)
    throw InputError(
        source, "dims",
        fmt::format("grid dimensions {}x{}x{} must all be > 0", dims.nx, dims.ny, dims.nz));
  if (spectral_count <= 0)
    throw InputError(source, "wavelengths_um", "a grid needs at least one spectral sample");
  std::uint64_t bytes = 0;
  const std::uint64_t channels = 3ull * static_cast<std::uint64_t>(spectral_count) + 1ull;
  if (__builtin_mul_overflow(static_cast<std::uint64_t>(dims.nx),
                             static_cast<std::uint64_t>(dims.ny), &bytes) ||
      __builtin_mul_overflow(bytes, static_cast<std::uint64_t>(dims.nz), &bytes) ||
      __builtin_mul_overflow(bytes, channels, &bytes) ||
      __builtin_mul_overflow(bytes, static_cast<std::uint64_t>(sizeof(float)), &bytes))
    throw InputError(source, "dims",
                     fmt::format("grid {}x{}x{} with {} channels overflows a 64-bit size", dims.nx,
                                 dims.ny, dims.nz, channels));
  check_memory(bytes, source, "dims",
               fmt::format("grid {}x{}x{} with {} channels", dims.nx, dims.ny, dims.nz, channels));
  return static_cast<std::size_t>(bytes);
}

VoxelGrid::VoxelGrid(GridDims dims, GridPlacement placement, std::vector<double> wavelengths_um,
                     const std::string& source)
    : dims_(dims), placement_(placement), wavelengths_um_(std::move(wavelengths_um)) {
  const std::size_t bytes = checked_storage_bytes(dims, spectral_count(), source);
  for (std::size_t k = 0; k < wavelengths_um_.size(); ++k) {
    const double w = wavelengths_um_[k];
    if (!(std::isfinite(w) && w > 0.0))
      throw InputError(source, fmt::format("wavelengths_um[{}]", k),
                       fmt::format("wavelength {} must be finite and > 0 µm", w));
    if (k > 0 && !(w > wavelengths_um_[k - 1]))
      throw InputError(source, "wavelengths_um", "wavelengths must be strictly increasing");
  }
  if (!(std::isfinite(placement.voxel_size_m) && placement.voxel_size_m > 0.0))
    throw InputError(source, "voxel_size_m",
                     fmt::format("voxel size {} must be finite and > 0 m", placement.voxel_size_m));
  if (!is_finite(placement.origin_m)) throw InputError(source, "origin_m", "origin must be finite");
  data_.assign(bytes / sizeof(float), 0.0f);
}

std::string VoxelGrid::channel_name(int c) const {
  const int n = spectral_count();
  if (c < n) return fmt::format("sigma_a_{:03d}", c);
  if (c < 2 * n) return fmt::format("sigma_s_{:03d}", c - n);
  if (c < 3 * n) return fmt::format("g_{:03d}", c - 2 * n);
  return "temperature";
}

void VoxelGrid::validate(const std::string& source) const {
  const int n = spectral_count();
  for (int c = 0; c < channel_count(); ++c) {
    const float* v = channel(c);
    const bool is_g = c >= 2 * n && c < 3 * n;
    for (int k = 0; k < dims_.nz; ++k)
      for (int j = 0; j < dims_.ny; ++j)
        for (int i = 0; i < dims_.nx; ++i) {
          const float x = v[index(i, j, k)];
          const char* problem = nullptr;
          if (!std::isfinite(x))
            problem = "is not finite";
          else if (is_g && !(x > -1.0f && x < 1.0f))
            problem = "is outside (-1, 1)";
          else if (!is_g && x < 0.0f)
            problem = "is negative";
          if (problem)
            throw InputError(source, fmt::format("{} voxel ({},{},{})", channel_name(c), i, j, k),
                             fmt::format("value {} {}", x, problem));
        }
  }
}

BBox3 VoxelGrid::world_bounds() const {
  BBox3 box;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 idx((corner & 1) ? dims_.nx - 0.5 : -0.5, (corner & 2) ? dims_.ny - 0.5 : -0.5,
                   (corner & 4) ? dims_.nz - 0.5 : -0.5);
    box.expand(placement_.index_to_world(idx));
  }
  return box;
}

}  // namespace obscura
