#pragma once
// One batch of camera rays marched over a frame's lattice records
// (render/lattice/lattice_view.h) at chosen spectral nodes: the work of the
// GPU's march kernel (gpu/cuda/march_kernels.cu) and of its reference on the
// CPU's threads (host_executor.h), which run the same march_item per item
// (docs/gpu.md). An item is one ray at one output, an output one spectral
// node of a sensor's band; items k·rays … (k + 1)·rays − 1 are output k's, so
// that neighbouring device threads march neighbouring pixels at the same node
// and read the same records.
//
// Plain data: pointers and numbers that both compilers lay out alike
// (static_asserts below), into host memory for the CPU, device memory for a
// device. Only standard headers and obscura's shared (core/host_device.h)
// headers are included, so the bare GPU check (gpu/check) builds it.
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "obscura/core/host_device.h"
#include "obscura/core/planck_table.h"
#include "obscura/core/ray.h"
#include "obscura/core/vec3.h"
#include "obscura/render/emission_absorption/emission_source.h"
#include "obscura/render/lattice/lattice_view.h"
#include "obscura/render/lattice/lattice_view_march.h"
#include "obscura/render/radiance_cache/cache_source.h"

namespace obscura {

// A camera ray as the march needs it: world origin (m), unit direction, and
// where it ends (the first surface, else +∞), m.
struct MarchRay {
  Vec3 origin;
  Vec3 direction;
  double t_end = 0.0;
};

// What a point of the march emits (render/lattice/lattice_view_march.h's
// Source): emission–absorption's σa B(T) (records of record::kMediumStride
// floats), or the radiance cache's σa B(T) + σs J (records with the light).
enum class MarchSource : std::int32_t { kEmission = 0, kCache = 1 };

struct MarchJob {
  LatticeView lattice;
  const float* const* records = nullptr;      // per distinct node u: its records
  const PlanckTableView* planck = nullptr;    // per distinct node u
  const double* sun_irradiance = nullptr;     // per distinct node u (kCache), W m⁻² µm⁻¹
  const std::int32_t* output_node = nullptr;  // per output k: its distinct node u
  const MarchRay* rays = nullptr;
  double* radiance = nullptr;       // per item: W m⁻² sr⁻¹ µm⁻¹ the medium sends
  double* transmittance = nullptr;  // per item: the medium's, to the ray's end
  // Per item: what the radiance behind the medium is seen through (kCache
  // with delta-M: e^{−∫(σt − f σs)}, cache_source.h; else the transmittance).
  double* attenuation = nullptr;
  std::uint32_t* cells = nullptr;  // per item: cells visited
  std::uint64_t ray_count = 0;
  std::int32_t outputs = 0;
  std::int32_t stride = record::kMediumStride;  // floats per record
  MarchSource source = MarchSource::kEmission;
  std::int32_t sh_degree = 0;      // kCache: the records' spherical-harmonic degree
  std::int32_t sun = 0;            // kCache: whether the sun shines
  std::int32_t peak_channel = -1;  // kCache: CacheLight::peak of this job's sensor
  Vec3 to_sun;                     // kCache: unit world direction towards the sun

  OBSCURA_HOST_DEVICE std::uint64_t items() const {
    return ray_count * static_cast<std::uint64_t>(outputs);
  }
};

static_assert(std::is_trivially_copyable_v<MarchRay> && sizeof(MarchRay) == 56 &&
              offsetof(MarchRay, direction) == 24 && offsetof(MarchRay, t_end) == 48);
static_assert(std::is_trivially_copyable_v<MarchJob> && std::is_standard_layout_v<MarchJob>);
static_assert(offsetof(MarchJob, records) == sizeof(LatticeView) &&
              offsetof(MarchJob, ray_count) == sizeof(LatticeView) + 72 &&
              offsetof(MarchJob, outputs) == sizeof(LatticeView) + 80 &&
              offsetof(MarchJob, to_sun) == sizeof(LatticeView) + 104 &&
              sizeof(MarchJob) == sizeof(LatticeView) + 128);
static_assert(sizeof(PlanckTableView) == 32);

// The spherical-harmonic degree whose light records are Stride floats
// (record::light_stride of degrees 0…3: 8, 12, 16, 24 floats); −1 for none,
// and for the CPU's higher degrees, which a device's kernels do not hold.
constexpr int sh_degree_of_stride(int stride) {
  for (int degree = 0; degree <= kMaxDeviceShDegree; ++degree)
    if (record::light_stride(sh_coefficient_count(degree)) == stride) return degree;
  return -1;
}

// Item `item` of the job: one ray at one output, marched with the source
// Kind over records of Stride floats (a kCache job's degree is
// sh_degree_of_stride(Stride), a constant here, so that a device keeps the
// harmonics in registers). Results equal, bit for bit, the CPU march of the
// same ray over all nodes of its band at once (lattice_march.h): each node's
// arithmetic is the same.
template <int Stride, MarchSource Kind>
OBSCURA_HOST_DEVICE void march_item(const MarchJob& job, std::uint64_t item) {
  const std::uint64_t i = item % job.ray_count;
  const auto k = static_cast<std::int32_t>(item / job.ray_count);
  const std::int32_t u = job.output_node[k];
  const MarchRay& r = job.rays[i];
  const Ray ray{r.origin, r.direction};
  const float* const records = job.records[u];
  double radiance = 0.0, transmittance = 1.0, attenuation = 1.0;
  std::uint64_t cells = 0;
  if constexpr (Kind == MarchSource::kEmission) {
    const EmissionSource source{job.planck + u};
    cells = march_lattice_view<Stride, 1>(job.lattice, &records, 1, ray, r.t_end, source, &radiance,
                                          &transmittance);
    attenuation = transmittance;
  } else {
    constexpr int kDegree = sh_degree_of_stride(Stride);
    static_assert(kDegree >= 0, "no light records are this long");
    const CacheLight light(r.direction, job.sun != 0, job.to_sun, job.sun_irradiance + u, kDegree,
                           job.peak_channel);
    if (job.peak_channel >= 0) {  // the whole phase function: no delta-M (cache_source.h)
      const CacheSource source{job.planck + u, light};
      cells = march_lattice_view<Stride, 1>(job.lattice, &records, 1, ray, r.t_end, source,
                                            &radiance, &transmittance);
      attenuation = transmittance;
    } else {
      const DeltaMCacheSource source{job.planck + u, light};
      cells = march_lattice_view<Stride, 1>(job.lattice, &records, 1, ray, r.t_end, source,
                                            &radiance, &transmittance, &attenuation);
    }
  }
  job.radiance[item] = radiance;
  job.transmittance[item] = transmittance;
  job.attenuation[item] = attenuation;
  job.cells[item] = static_cast<std::uint32_t>(cells);
}

// The (stride, source) pairs there are kernels for: emission–absorption over
// medium records, the radiance cache over light records of degree 0…3.
constexpr bool march_supported(int stride, MarchSource source) {
  return source == MarchSource::kEmission ? stride == record::kMediumStride
                                          : sh_degree_of_stride(stride) >= 0;
}

// Calls f(std::integral_constant<int, Stride>{}) for light records of
// `stride` floats (sh_degree_of_stride(stride) ≥ 0): the one place that turns
// a light stride into a template argument.
template <class F>
void dispatch_light_stride(int stride, F&& f) {
  constexpr int s0 = record::light_stride(sh_coefficient_count(0)),
                s1 = record::light_stride(sh_coefficient_count(1)),
                s2 = record::light_stride(sh_coefficient_count(2)),
                s3 = record::light_stride(sh_coefficient_count(3));
  if (stride == s0)
    f(std::integral_constant<int, s0>{});
  else if (stride == s1)
    f(std::integral_constant<int, s1>{});
  else if (stride == s2)
    f(std::integral_constant<int, s2>{});
  else
    f(std::integral_constant<int, s3>{});
}

// Calls f(std::integral_constant<int, Stride>{},
// std::integral_constant<MarchSource, Kind>{}) for the job's stride and
// source (march_supported must hold).
template <class F>
void dispatch_march(const MarchJob& job, F&& f) {
  using E = std::integral_constant<MarchSource, MarchSource::kEmission>;
  using C = std::integral_constant<MarchSource, MarchSource::kCache>;
  if (job.source == MarchSource::kEmission)
    f(std::integral_constant<int, record::kMediumStride>{}, E{});
  else
    dispatch_light_stride(job.stride, [&](auto stride) { f(stride, C{}); });
}

}  // namespace obscura
