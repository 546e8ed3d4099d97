#include "obscura/gpu/lattice_batch_integrator.h"

#include <chrono>
#include <numeric>
#include <string>

#include "obscura/core/error.h"
#include "obscura/gpu/cuda/cuda_error.h"

namespace obscura {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

InputError not_one_grid() {
  return InputError("", "render/device",
                    "\"gpu\" marches a cloud that is one voxel grid (the radiance cache's lattice "
                    "at the grid's own voxel size, not periodic); this frame's medium is not one "
                    "(several clouds, a box, voxel_m or lateral_period_m set): set \"device\": "
                    "\"cpu\" (docs/gpu.md)");
}

// An executor call, its CUDA failures (out of device memory, a fault) said as
// obscura errors: the user's to act on, not a bug report.
template <class F>
void on_device(F&& f) {
  try {
    f();
  } catch (const CudaError& e) {
    throw Error(std::string("gpu: ") + e.what());
  }
}

}  // namespace

LatticeBatchIntegrator::LatticeBatchIntegrator(const Scene& scene, const FrameSpectra& spectra,
                                               std::unique_ptr<LatticeExecutor> executor,
                                               const ProcessGroup& processes,
                                               const PreparationProgress& progress)
    : BatchIntegrator(scene, spectra),
      distinct_(distinct_nodes(spectra)),
      executor_(std::move(executor)) {
  const RenderMethod method = scene.settings.method;
  if (method != RenderMethod::kEmissionAbsorption && method != RenderMethod::kRadianceCache)
    throw InputError("", "render/device",
                     std::string("\"gpu\" renders \"emission-absorption\" and \"radiance-cache\" "
                                 "only, not \"") +
                         std::string(render_method_name(method)) + "\" (docs/gpu.md)");
  for (std::size_t s = 0; s < spectra.size(); ++s) {
    MarchRequest& request = requests_.emplace_back();
    for (const std::vector<int>& band : distinct_.index[s])
      request.output_node.insert(request.output_node.end(), band.begin(), band.end());
  }
  if (!scene.medium || distinct_.nodes.empty()) return;  // nothing to march

  const auto start = std::chrono::steady_clock::now();
  std::vector<SpectralLerp> lerps;
  for (const SpectralNode& nd : distinct_.nodes) lerps.push_back(nd.lerp());
  const LatticeVolume* volume = nullptr;
  MarchSource source = MarchSource::kEmission;
  if (method == RenderMethod::kEmissionAbsorption) {
    grid_ = grid_records(*scene.medium, lerps, record::kMediumStride, scene.settings.threads);
    if (!grid_.volume) throw not_one_grid();
    volume = grid_.volume.get();
  } else {
    // Only camera rays read it: the light where each node's sensors look.
    cache_ = std::make_unique<RadianceCache>(
        scene, distinct_.nodes, processes, RadianceCache::SunDepths::kByCaller,
        sensors_of_nodes(distinct_), photons_of_nodes(scene, distinct_), progress);
    if (!cache_->volume().has_medium()) throw not_one_grid();
    volume = &cache_->volume();
    source = MarchSource::kCache;
    preparation_.photons = cache_->photons_stored();
    preparation_.photon_bytes = cache_->memory_bytes();
    preparation_.trace_seconds = cache_->photon_seconds;
    preparation_.walks = cache_->photon_walks();
  }

  FrameLattice frame;
  frame.view = volume->view();
  frame.stride = volume->stride();
  for (std::size_t u = 0; u < distinct_.nodes.size(); ++u) {
    const SpectralNode& nd = distinct_.nodes[u];
    frame.records.push_back(volume->records(static_cast<int>(u)));
    frame.planck.push_back(nd.planck_table->view());
    frame.sun_irradiance.push_back(
        scene.sun.enabled && cache_ ? scene.sun.irradiance(nd.wavelength_um) : 0.0);
  }
  for (std::size_t s = 0; s < requests_.size(); ++s) {
    MarchRequest& request = requests_[s];
    request.source = source;
    if (cache_) {
      request.peak_channel = cache_->peak_channel(static_cast<int>(s));
      request.sh_degree = cache_->sh_degree();
      request.sun = scene.sun.enabled;
      if (scene.sun.enabled) request.to_sun = scene.sun.direction();
    }
  }
  on_device([&] {
    executor_->load(frame);
    if (cache_ && cache_->has_sun()) executor_->sun_depths(scene.sun.direction());
  });
  preparation_.seconds = seconds_since(start);
  preparation_.build_seconds = preparation_.seconds - preparation_.trace_seconds;
}

LatticeBatchIntegrator::~LatticeBatchIntegrator() = default;

const LatticeVolume* LatticeBatchIntegrator::volume() const {
  return cache_ ? &cache_->volume() : grid_.volume.get();
}

PreparationStats LatticeBatchIntegrator::preparation(int sensor) const {
  return sensor == 0 ? preparation_ : PreparationStats{};
}

void LatticeBatchIntegrator::add_surface_light(const CameraRay& ray, int sensor, int band,
                                               double* behind) const {
  if (!cache_) return;
  add_ground_light(
      scene(), *cache_, ray,
      spectra()[static_cast<std::size_t>(sensor)][static_cast<std::size_t>(band)],
      distinct_.index[static_cast<std::size_t>(sensor)][static_cast<std::size_t>(band)].data(),
      behind);
}

void LatticeBatchIntegrator::march_batch(int sensor, std::span<const CameraRay> rays,
                                         MediumBatch& out) const {
  const std::vector<SpectralNodes>& bands = spectra()[static_cast<std::size_t>(sensor)];
  const std::vector<int> first = band_output_offsets(bands);
  const std::size_t count = rays.size(), items = count * static_cast<std::size_t>(first.back());
  out.count = count;
  out.band_cells.assign(bands.size(), 0);
  if (!volume()) {  // no medium: nothing in front of the background
    out.radiance.assign(items, 0.0);
    out.transmittance.assign(items, 1.0);
    out.attenuation.assign(items, 1.0);
    return;
  }
  std::vector<MarchRay> march_rays(count);
  for (std::size_t i = 0; i < count; ++i)
    march_rays[i] = {rays[i].ray.origin, rays[i].ray.direction, rays[i].t_end()};
  MarchResult result;
  on_device(
      [&] { executor_->march(requests_[static_cast<std::size_t>(sensor)], march_rays, result); });
  out.radiance = std::move(result.radiance);
  out.transmittance = std::move(result.transmittance);
  out.attenuation = std::move(result.attenuation);
  // Cells per band, as the CPU's integrators count them: once per ray and
  // band (all nodes of a band cross the same cells: its first node's count).
  for (std::size_t b = 0; b < bands.size(); ++b)
    if (first[b + 1] > first[b])
      out.band_cells[b] =
          std::accumulate(result.cells.begin() + first[b] * count,
                          result.cells.begin() + (first[b] + 1) * count, std::uint64_t{0});
}

}  // namespace obscura
