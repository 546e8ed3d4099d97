#include "procedural_cloud.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "obscura/render/radiance_cache/spherical_harmonics.h"

namespace obscura::gpu_check {
namespace {

constexpr int kBlock = LatticeView::kBlock;

// ρ at world point p.
double density(const CloudSpec& spec, const Vec3& p) {
  double rho = 0.0;
  for (const Lobe& lobe : spec.lobes) {
    const Vec3 d = p - lobe.centre_m;
    rho += lobe.weight * std::exp(-0.5 * dot(d, d) / (lobe.sigma_m * lobe.sigma_m));
  }
  return rho;
}

}  // namespace

ProceduralCloud::ProceduralCloud(const CloudSpec& spec)
    : spec_(spec),
      stride_(spec.sh_degree < 0 ? record::kMediumStride
                                 : record::light_stride(sh_coefficient_count(spec.sh_degree))) {
  const std::array<int, 3>& v = spec.voxels;
  const int nodes_u = static_cast<int>(spec.wavelengths_um.size());
  if (nodes_u == 0 || spec.peak_sigma_a.size() != spec.wavelengths_um.size() ||
      spec.peak_sigma_s.size() != spec.wavelengths_um.size())
    throw std::invalid_argument("procedural cloud: one σa and σs peak per wavelength");
  const double h = spec.voxel_m;
  std::array<int, 3> dims{}, block_dims{};
  for (int a = 0; a < 3; ++a) {
    dims[a] = v[a] + 2;  // the voxel centres and a rim node each side
    block_dims[a] = (dims[a] + kBlock - 1) / kBlock;
  }
  // ρ per voxel, and its peak.
  const std::size_t voxel_count = static_cast<std::size_t>(v[0]) * v[1] * v[2];
  std::vector<float> rho(voxel_count);
  auto voxel_centre = [&](int i, int j, int k) {
    return spec.origin_m + spec.rotation * Vec3((i + 0.5) * h, (j + 0.5) * h, (k + 0.5) * h);
  };
  double peak = 0.0;
  for (int k = 0; k < v[2]; ++k)
    for (int j = 0; j < v[1]; ++j)
      for (int i = 0; i < v[0]; ++i) {
        const double r = density(spec, voxel_centre(i, j, k));
        rho[(static_cast<std::size_t>(k) * v[1] + j) * v[0] + i] = static_cast<float>(r);
        peak = std::max(peak, r);
      }
  for (float& r : rho)
    if (r < spec.cutoff * peak) r = 0.0f;
  // The voxel node (i, j, k) holds: the rim repeats the edge.
  auto rho_at_node = [&](int i, int j, int k) {
    const int x = std::clamp(i - 1, 0, v[0] - 1), y = std::clamp(j - 1, 0, v[1] - 1),
              z = std::clamp(k - 1, 0, v[2] - 1);
    return rho[(static_cast<std::size_t>(z) * v[1] + y) * v[0] + x];
  };
  // A block is held when a node within one node of it holds medium.
  block_index_.assign(static_cast<std::size_t>(block_dims[0]) * block_dims[1] * block_dims[2], -1);
  for (int bz = 0; bz < block_dims[2]; ++bz)
    for (int by = 0; by < block_dims[1]; ++by)
      for (int bx = 0; bx < block_dims[0]; ++bx) {
        bool any = false;
        for (int k = std::max(0, bz * kBlock - 1);
             !any && k <= std::min(dims[2] - 1, bz * kBlock + kBlock); ++k)
          for (int j = std::max(0, by * kBlock - 1);
               !any && j <= std::min(dims[1] - 1, by * kBlock + kBlock); ++j)
            for (int i = std::max(0, bx * kBlock - 1);
                 !any && i <= std::min(dims[0] - 1, bx * kBlock + kBlock); ++i)
              any = rho_at_node(i, j, k) != 0.0f;
        if (!any) continue;
        block_index_[static_cast<std::size_t>(bx) +
                     static_cast<std::size_t>(block_dims[0]) *
                         (by + static_cast<std::size_t>(block_dims[1]) * bz)] =
            static_cast<std::int32_t>(blocks_.size());
        blocks_.push_back({bx, by, bz});
      }
  const std::uint64_t slot_count = slots();
  occupied_.assign(slot_count + 1, 0);
  records_.assign(static_cast<std::size_t>(nodes_u),
                  std::vector<float>((slot_count + 1) * static_cast<std::size_t>(stride_), 0.0f));
  const int sh_count = spec.sh_degree < 0 ? 0 : sh_coefficient_count(spec.sh_degree);
  for (std::size_t b = 0; b < blocks_.size(); ++b)
    for (int local = 0; local < LatticeView::kBlockNodes; ++local) {
      const int i = blocks_[b][0] * kBlock + local % kBlock,
                j = blocks_[b][1] * kBlock + (local / kBlock) % kBlock,
                k = blocks_[b][2] * kBlock + local / (kBlock * kBlock);
      if (i >= dims[0] || j >= dims[1] || k >= dims[2]) continue;
      const std::size_t slot = b * LatticeView::kBlockNodes + static_cast<std::size_t>(local);
      const double r = rho_at_node(i, j, k);
      occupied_[slot] = r != 0.0 ? 1 : 0;
      // The node's world position (its voxel's centre; the rim's lies outside).
      const Vec3 p = voxel_centre(i - 1, j - 1, k - 1);
      for (int u = 0; u < nodes_u; ++u) {
        float* rec = records_[static_cast<std::size_t>(u)].data() + slot * stride_;
        const double sigma_s = r * spec.peak_sigma_s[static_cast<std::size_t>(u)];
        rec[record::kSigmaA] =
            static_cast<float>(r * spec.peak_sigma_a[static_cast<std::size_t>(u)]);
        rec[record::kSigmaS] = static_cast<float>(sigma_s);
        rec[record::kTemperature] =
            static_cast<float>(spec.ambient_k + spec.excess_k * (peak > 0 ? r / peak : 0.0));
        rec[record::kSigmaSG] = static_cast<float>(sigma_s * spec.g);
        if (spec.sh_degree < 0) continue;
        rec[record::kSunVisibility] = p.z < spec.shadow_below_m ? 0.0f : 1.0f;
        // Incident radiance mostly from above and the sun's side, varying
        // smoothly through the cloud and with wavelength.
        const double a = spec.sh_amplitude * (1.0 + 0.3 * std::sin(0.21 * p.x + 0.5 * u)) *
                         (1.0 + 0.2 * std::cos(0.17 * p.y));
        for (int c = 0; c < sh_count; ++c) {
          const int l = c == 0 ? 0 : c < 4 ? 1 : c < 9 ? 2 : 3;
          rec[record::kSh + c] =
              static_cast<float>(a * std::pow(0.45, l) * std::cos(0.7 * c + 0.05 * p.z + 0.3 * u));
        }
      }
    }
  view_.origin_m = spec.origin_m + spec.rotation * Vec3(-0.5 * h, -0.5 * h, -0.5 * h);
  view_.to_lattice_axes = spec.rotation.transposed();
  view_.spacing_m = h;
  for (int a = 0; a < 3; ++a) {
    view_.dims[a] = dims[a];
    view_.block_dims[a] = block_dims[a];
  }
  view_.block_index = block_index_.data();
  view_.blocks = blocks_.data();
  view_.occupied = occupied_.data();
  view_.zero_slot = slot_count;
  view_.domain = BBox3(Vec3(0.5, 0.5, 0.5), Vec3(v[0] + 0.5, v[1] + 0.5, v[2] + 0.5));
  for (const double wl : spec.wavelengths_um) planck_.push_back(std::make_unique<PlanckTable>(wl));
}

FrameLattice ProceduralCloud::frame() const {
  FrameLattice f;
  f.view = view_;
  f.stride = stride_;
  for (std::size_t u = 0; u < records_.size(); ++u) {
    f.records.push_back(records_[u].data());
    f.planck.push_back(planck_[u]->view());
    // A sun of 1000 W m⁻² µm⁻¹ falling off into the infrared, when there is light.
    f.sun_irradiance.push_back(spec_.sh_degree < 0 ? 0.0 : 1000.0 / spec_.wavelengths_um[u]);
  }
  return f;
}

std::uint64_t ProceduralCloud::record_bytes() const {
  return records_.size() * (slots() + 1) * static_cast<std::uint64_t>(stride_) * sizeof(float);
}

Vec3 ProceduralCloud::centre_m() const {
  const double h = spec_.voxel_m;
  return spec_.origin_m + spec_.rotation * Vec3(0.5 * spec_.voxels[0] * h,
                                                0.5 * spec_.voxels[1] * h,
                                                0.5 * spec_.voxels[2] * h);
}

}  // namespace obscura::gpu_check
