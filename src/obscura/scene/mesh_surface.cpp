#include "obscura/scene/mesh_surface.h"

#include <embree3/rtcore.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "obscura/core/error.h"

namespace obscura {
namespace {

// Embree reports errors through a callback inside its C API; exceptions must
// not unwind through it, so the callback keeps the message (per thread, as
// Embree keeps its error codes) and check_embree() throws it as an Error.
thread_local std::string t_embree_error;

const char* error_name(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE:
      return "no error";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
      return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
      return "cancelled";
    default:
      return "unknown error";
  }
}

void on_embree_error(void*, RTCError code, const char* message) {
  if (t_embree_error.empty())
    t_embree_error = fmt::format("{} ({})", error_name(code), message ? message : "no message");
}

void check_embree(RTCDevice device, const char* what) {
  const RTCError code = rtcGetDeviceError(device);
  if (code == RTC_ERROR_NONE && t_embree_error.empty()) return;
  std::string message = t_embree_error.empty() ? error_name(code) : std::move(t_embree_error);
  t_embree_error.clear();
  throw Error(fmt::format("Embree: {}: {}", what, message));
}

// The process's one Embree device, created on first use (thread-safe: a
// function-local static) and released at exit; every scene holds a reference.
class EmbreeDevice {
 public:
  EmbreeDevice() : device_(rtcNewDevice(nullptr)) {
    if (!device_)
      throw Error(fmt::format("Embree: cannot create a device: {}",
                              error_name(rtcGetDeviceError(nullptr))));
    rtcSetDeviceErrorFunction(device_, on_embree_error, nullptr);
    // Hits are accepted or rejected in double precision by a filter (mesh_surface.h).
    if (!rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_FILTER_FUNCTION_SUPPORTED)) {
      rtcReleaseDevice(device_);
      throw Error(
          "Embree: this build of Embree has no filter functions (EMBREE_FILTER_FUNCTION), "
          "which triangle-mesh surfaces need");
    }
  }
  ~EmbreeDevice() { rtcReleaseDevice(device_); }
  EmbreeDevice(const EmbreeDevice&) = delete;
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;
  RTCDevice get() const { return device_; }

 private:
  RTCDevice device_;
};

RTCDevice embree_device() {
  static const EmbreeDevice device;
  return device.get();
}

// What the filter needs beyond Embree's context: the caller's ray in double
// precision and its window. Embree passes the context pointer through to the
// filter, so the context is the first member (Embree's documented extension).
struct FilterContext {
  RTCIntersectContext base;
  const MeshSurface* surface;
  const Ray* ray;
  double t_min, t_max;
};
static_assert(offsetof(FilterContext, base) == 0);

void filter_hits(const RTCFilterFunctionNArguments* args) {
  const auto* ctx = reinterpret_cast<const FilterContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (!args->valid[i]) continue;
    const double t = ctx->surface->plane_distance(RTCHitN_primID(args->hit, args->N, i), *ctx->ray);
    if (!(t > ctx->t_min && t < ctx->t_max)) args->valid[i] = 0;
  }
}

}  // namespace

void MeshSurface::SceneRelease::operator()(RTCSceneTy* scene) const {
  RTCDevice device = rtcGetSceneDevice(scene);
  rtcReleaseScene(scene);
  rtcReleaseDevice(device);
}

MeshSurface::MeshSurface(std::string name, SurfaceMaterial material, const TriangleMesh& mesh)
    : Surface(std::move(name), std::move(material)), vertices_(mesh.vertices) {
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const double area2 = mesh.double_area(i);
    if (!(area2 > 0) || !std::isfinite(area2)) continue;
    triangles_.push_back(mesh.triangles[i]);
    for (int k = 0; k < 3; ++k) bounds_.expand(vertices_[mesh.triangles[i][k]]);
  }
  if (triangles_.empty())
    throw Error(
        fmt::format("surface '{}': the mesh has no triangle with a non-zero area", this->name()));
  if (triangles_.size() > std::numeric_limits<unsigned>::max() / 3)
    throw Error(fmt::format("surface '{}': too many triangles for Embree", this->name()));
  centre_ = bounds_.center();
  margin_ = 1e-4 * std::max(length(bounds_.extent()), 1e-6);
  padded_bounds_ = BBox3(bounds_.lo - Vec3(margin_, margin_, margin_),
                         bounds_.hi + Vec3(margin_, margin_, margin_));

  RTCDevice device = embree_device();
  rtcRetainDevice(device);
  scene_.reset(rtcNewScene(device));
  if (!scene_) {
    rtcReleaseDevice(device);
    check_embree(device, "creating a scene");
    throw Error("Embree: cannot create a scene");
  }
  rtcSetSceneFlags(scene_.get(), RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene_.get(), RTC_BUILD_QUALITY_HIGH);
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  check_embree(device, "creating a triangle geometry");
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertices_.size()));
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0,
                                                             RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                             triangles_.size()));
  if (!v || !idx) {
    rtcReleaseGeometry(geometry);
    check_embree(device, "allocating mesh buffers");
    throw Error("Embree: cannot allocate mesh buffers");
  }
  // Vertices relative to the centre: float keeps ~7 digits of the mesh's size.
  for (std::size_t i = 0; i < vertices_.size(); ++i) {
    const Vec3 p = vertices_[i] - centre_;
    v[3 * i] = static_cast<float>(p.x);
    v[3 * i + 1] = static_cast<float>(p.y);
    v[3 * i + 2] = static_cast<float>(p.z);
  }
  for (std::size_t i = 0; i < triangles_.size(); ++i)
    for (int k = 0; k < 3; ++k) idx[3 * i + k] = triangles_[i][k];
  rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_HIGH);
  rtcSetGeometryIntersectFilterFunction(geometry, filter_hits);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene_.get(), geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene_.get());
  check_embree(device, fmt::format("building the BVH of surface '{}'", this->name()).c_str());
}

MeshSurface::~MeshSurface() = default;

Vec3 MeshSurface::area_normal(std::size_t index) const {
  const auto& tri = triangles_[index];
  const Vec3& a = vertices_[tri[0]];
  return cross(vertices_[tri[1]] - a, vertices_[tri[2]] - a);
}

double MeshSurface::plane_distance(std::size_t index, const Ray& ray) const {
  return plane_distance(vertices_[triangles_[index][0]], area_normal(index), ray);
}

bool MeshSurface::intersect(const Ray& ray, double t_min, double t_max, SurfaceHit& hit) const {
  const double t_lo = std::max(t_min, 0.0);
  // The part of the window inside the mesh's box, widened by the margin.
  double t0 = t_lo, t1 = t_max;
  if (!(t0 < t1) || !padded_bounds_.intersect(ray, t0, t1)) return false;
  // Only a ray that may reach the mesh is checked for NaN and infinity before
  // Embree sees it (most of a photon's flights miss the box: the same
  // results, fewer instructions).
  if (!is_finite(ray.origin) || !is_finite(ray.direction)) return false;
  // Embree's ray starts `margin_` before the box; its window covers the
  // clipped one with margin to spare, and the filter applies the exact one.
  const double shift = t0 - margin_;
  const Vec3 o = ray.at(shift) - centre_;
  RTCRayHit rh{};
  rh.ray.org_x = static_cast<float>(o.x);
  rh.ray.org_y = static_cast<float>(o.y);
  rh.ray.org_z = static_cast<float>(o.z);
  rh.ray.dir_x = static_cast<float>(ray.direction.x);
  rh.ray.dir_y = static_cast<float>(ray.direction.y);
  rh.ray.dir_z = static_cast<float>(ray.direction.z);
  rh.ray.tnear = 0.0f;
  rh.ray.tfar =
      static_cast<float>(std::min(t1 - shift + margin_, double(std::numeric_limits<float>::max())));
  rh.ray.mask = ~0u;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  FilterContext ctx{{}, this, &ray, t_lo, t_max};
  rtcInitIntersectContext(&ctx.base);
  rtcIntersect1(scene_.get(), &ctx.base, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  // The filter accepted this triangle: its distance and normal in double precision.
  const Vec3 area_n = area_normal(rh.hit.primID);
  hit.t = plane_distance(vertices_[triangles_[rh.hit.primID][0]], area_n, ray);
  const Vec3 n = normalize(area_n);
  hit.normal = dot(n, ray.direction) > 0 ? -n : n;
  return true;
}

}  // namespace obscura
