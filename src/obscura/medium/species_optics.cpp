#include "obscura/medium/species_optics.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <atomic>
#include <cmath>

#include "obscura/core/error.h"
#include "obscura/core/parallel.h"

namespace obscura {

void check_species_optics(const SpeciesOptics& optics, const std::vector<double>& wavelengths_um,
                          const std::string& source, const std::string& field) {
  const std::string who = fmt::format("species '{}'", optics.name);
  if (optics.name.empty()) throw InputError(source, field + "/name", "a species needs a name");
  if (optics.wavelengths_um != wavelengths_um)
    throw InputError(
        source, field + "/wavelengths_um",
        fmt::format("{} has optics at {} µm, but the cloud's wavelengths are {} µm; "
                    "they must be exactly the same",
                    who, fmt::join(optics.wavelengths_um, ", "), fmt::join(wavelengths_um, ", ")));
  const std::size_t n = wavelengths_um.size();
  const auto check_size = [&](const std::vector<double>& v, const char* member) {
    if (v.size() != n)
      throw InputError(source, field + "/" + member,
                       fmt::format("{} has {} values for {} wavelengths", who, v.size(), n));
  };
  check_size(optics.mass_absorption_m2_g, "mass_absorption_m2_g");
  check_size(optics.mass_scattering_m2_g, "mass_scattering_m2_g");
  check_size(optics.asymmetry, "asymmetry");
  for (std::size_t k = 0; k < n; ++k) {
    for (const auto& [v, member] :
         {std::pair{optics.mass_absorption_m2_g[k], "mass_absorption_m2_g"},
          std::pair{optics.mass_scattering_m2_g[k], "mass_scattering_m2_g"}})
      if (!(std::isfinite(v) && v >= 0))
        throw InputError(
            source, fmt::format("{}/{}/{}", field, member, k),
            fmt::format("{} at {} µm: {} m2/g must be finite and >= 0", who, wavelengths_um[k], v));
    if (!(std::abs(optics.asymmetry[k]) < 1))
      throw InputError(source, fmt::format("{}/asymmetry/{}", field, k),
                       fmt::format("{} at {} µm: g = {} must lie in (-1, 1)", who,
                                   wavelengths_um[k], optics.asymmetry[k]));
  }
}

std::size_t SpeciesCloud::memory_bytes() const {
  std::size_t floats = temperature_k.size();
  for (const auto& c : concentration_g_m3) floats += c.size();
  return floats * sizeof(float);
}

std::string species_concentration_name(int s) { return fmt::format("concentration_{:03d}", s); }

namespace {

// Throws naming the first voxel of `values` that is not finite and >= 0.
void check_nonnegative(const std::vector<float>& values, const GridDims& d,
                       const std::string& source, const std::string& name, const char* units) {
  for (std::size_t v = 0; v < values.size(); ++v) {
    const float x = values[v];
    if (std::isfinite(x) && x >= 0.0f) continue;
    const std::size_t i = v % d.nx, j = (v / d.nx) % d.ny,
                      k = v / (static_cast<std::size_t>(d.nx) * d.ny);
    throw InputError(source, fmt::format("{} voxel ({},{},{})", name, i, j, k),
                     fmt::format("value {} {} must be finite and >= 0", x, units));
  }
}

}  // namespace

void validate_species_cloud(const SpeciesCloud& cloud, const std::string& source) {
  const GridDims& d = cloud.dims;
  if (d.nx <= 0 || d.ny <= 0 || d.nz <= 0)
    throw InputError(source, "dims",
                     fmt::format("grid dimensions {}x{}x{} must all be > 0", d.nx, d.ny, d.nz));
  const std::vector<double>& w = cloud.wavelengths_um;
  if (w.empty())
    throw InputError(source, "wavelengths_um", "a cloud needs at least one wavelength");
  for (std::size_t k = 0; k < w.size(); ++k)
    if (!(std::isfinite(w[k]) && w[k] > 0) || (k > 0 && !(w[k] > w[k - 1])))
      throw InputError(source, fmt::format("wavelengths_um[{}]", k),
                       fmt::format("wavelength {} µm: wavelengths must be finite, > 0 and strictly "
                                   "increasing",
                                   w[k]));
  const std::size_t species = cloud.species.size();
  if (species == 0 || species > 999)  // grid names carry three digits
    throw InputError(source, "species", fmt::format("{} species; a cloud needs 1 to 999", species));
  for (std::size_t s = 0; s < species; ++s)
    check_species_optics(cloud.species[s], w, source, fmt::format("species/{}", s));
  if (cloud.concentration_g_m3.size() != species)
    throw InputError(source, "concentration",
                     fmt::format("{} concentration arrays for {} species",
                                 cloud.concentration_g_m3.size(), species));
  const std::size_t count = d.count();
  for (std::size_t s = 0; s < species; ++s) {
    const std::string name = species_concentration_name(static_cast<int>(s));
    if (cloud.concentration_g_m3[s].size() != count)
      throw InputError(
          source, name,
          fmt::format("{} values for {}x{}x{} voxels (species '{}')",
                      cloud.concentration_g_m3[s].size(), d.nx, d.ny, d.nz, cloud.species[s].name));
    check_nonnegative(cloud.concentration_g_m3[s], d, source, name, "g/m3");
  }
  if (cloud.temperature_k.size() != count)
    throw InputError(
        source, "temperature",
        fmt::format("{} values for {}x{}x{} voxels", cloud.temperature_k.size(), d.nx, d.ny, d.nz));
  check_nonnegative(cloud.temperature_k, d, source, "temperature", "K");
}

VoxelGrid expand_species(const SpeciesCloud& cloud, const std::string& source) {
  validate_species_cloud(cloud, source);
  VoxelGrid grid(cloud.dims, cloud.placement, cloud.wavelengths_um, source);  // checks memory
  const std::size_t ns = cloud.species.size();
  const int nk = grid.spectral_count();
  // g of a clear voxel: the species' g weighted by k_sca (see the header).
  std::vector<double> g_clear(nk, 0.0);
  for (int k = 0; k < nk; ++k) {
    double ks = 0;
    for (const SpeciesOptics& o : cloud.species) ks += o.mass_scattering_m2_g[k];
    if (ks > 0)
      for (const SpeciesOptics& o : cloud.species)
        g_clear[k] += o.mass_scattering_m2_g[k] / ks * o.asymmetry[k];
  }
  const std::size_t slice = static_cast<std::size_t>(cloud.dims.nx) * cloud.dims.ny;
  // Set where a value left the valid range (a product beyond the float range,
  // or g rounded to ±1): the grid's own check then names the voxel.
  std::atomic<bool> invalid{false};
  // Voxels are independent: z-slices in parallel, the same result for any thread count.
  parallel_for(static_cast<std::size_t>(cloud.dims.nz), 0, [&](std::size_t z) {
    const std::size_t begin = z * slice, end = begin + slice;
    std::vector<double> ws(ns);  // c_s k_sca,s of one voxel
    for (int k = 0; k < nk; ++k) {
      float* sa = grid.sigma_a(k);
      float* ss = grid.sigma_s(k);
      float* g = grid.g(k);
      for (std::size_t v = begin; v < end; ++v) {
        double a = 0, s = 0;
        for (std::size_t i = 0; i < ns; ++i) {
          const double c = cloud.concentration_g_m3[i][v];
          a += c * cloud.species[i].mass_absorption_m2_g[k];
          ws[i] = c * cloud.species[i].mass_scattering_m2_g[k];
          s += ws[i];
        }
        double gv = g_clear[k];
        if (s > 0) {
          // Weights ws/s: a lone scatterer's is exactly 1, so its g is kept bit for bit.
          gv = 0;
          for (std::size_t i = 0; i < ns; ++i) gv += ws[i] / s * cloud.species[i].asymmetry[k];
        }
        sa[v] = static_cast<float>(a);
        ss[v] = static_cast<float>(s);
        g[v] = static_cast<float>(gv);
        if (!(std::isfinite(sa[v]) && std::isfinite(ss[v]) && std::abs(g[v]) < 1.0f))
          invalid.store(true, std::memory_order_relaxed);
      }
    }
    float* t = grid.temperature();
    for (std::size_t v = begin; v < end; ++v) t[v] = cloud.temperature_k[v];
  });
  if (invalid.load()) grid.validate(source);  // throws naming the first bad voxel
  return grid;
}

}  // namespace obscura
