#include "obscura/gpu/host_executor.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>

#include "obscura/gpu/sun_depth_job.h"

namespace obscura {
namespace {

// body(item) for every item in [0, count) on `threads` threads, handing out
// chunks of items as threads become free (rays differ widely in cost).
template <class Body>
void for_items(std::uint64_t count, int threads, const Body& body) {
  constexpr std::uint64_t kChunk = 1024;
  std::atomic<std::uint64_t> next{0};
  auto work = [&] {
    for (;;) {
      const std::uint64_t begin = next.fetch_add(kChunk);
      if (begin >= count) return;
      const std::uint64_t end = std::min(count, begin + kChunk);
      for (std::uint64_t item = begin; item < end; ++item) body(item);
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

HostExecutor::HostExecutor(int threads) : threads_(std::max(1, threads)) {}

std::string HostExecutor::name() const {
  return "cpu (" + std::to_string(threads_) + (threads_ == 1 ? " thread)" : " threads)");
}

void HostExecutor::load(const FrameLattice& frame) {
  const auto start = std::chrono::steady_clock::now();
  const LatticeView& v = frame.view;
  block_index_.assign(v.block_index, v.block_index + frame.block_grid_size());
  blocks_.assign(v.blocks, v.blocks + frame.block_count());
  occupied_.assign(v.occupied, v.occupied + frame.slot_count() + 1);
  const std::size_t floats = (frame.slot_count() + 1) * static_cast<std::size_t>(frame.stride);
  records_.clear();
  for (const float* r : frame.records) records_.emplace_back(r, r + floats);
  planck_cubic_.clear();
  frame_ = frame;
  for (std::size_t u = 0; u < frame.planck.size(); ++u) {
    const double* c = frame.planck[u].cubic;
    planck_cubic_.emplace_back(c, c + 4 * static_cast<std::size_t>(kMaxTableTemperatureK));
    frame_.planck[u].cubic = planck_cubic_.back().data();
  }
  for (std::size_t u = 0; u < records_.size(); ++u) frame_.records[u] = records_[u].data();
  frame_.view = view();
  times_ = {seconds_since(start), 0.0};
}

LatticeView HostExecutor::view() const {
  LatticeView v = frame_.view;
  v.block_index = block_index_.data();
  v.blocks = blocks_.data();
  v.occupied = occupied_.data();
  return v;
}

void HostExecutor::sun_depths(const Vec3& to_sun) {
  const auto start = std::chrono::steady_clock::now();
  if (sh_degree_of_stride(frame_.stride) < 0)
    throw std::invalid_argument("sun depths: the records hold no light");
  std::vector<float*> records;
  for (std::vector<float>& r : records_) records.push_back(r.data());
  SunDepthJob job;
  job.lattice = frame_.view;
  job.records = records.data();
  job.slot_count = frame_.slot_count();
  job.nodes = static_cast<std::int32_t>(records.size());
  job.stride = frame_.stride;
  job.to_sun_lattice = frame_.view.to_lattice_direction(to_sun);
  dispatch_sun_depths(job, [&](auto stride) {
    for_items(job.items(), threads_,
              [&](std::uint64_t item) { sun_depth_item<decltype(stride)::value>(job, item); });
  });
  times_ = {0.0, seconds_since(start)};
}

void HostExecutor::march(const MarchRequest& request, std::span<const MarchRay> rays,
                         MarchResult& result) {
  const auto start = std::chrono::steady_clock::now();
  MarchJob job = make_march_job(frame_.view, frame_.stride, frame_.nodes(), request, rays.size());
  const std::uint64_t items = job.items();
  result.radiance.assign(items, 0.0);
  result.transmittance.assign(items, 1.0);
  result.attenuation.assign(items, 1.0);
  result.cells.assign(items, 0);
  job.records = frame_.records.data();
  job.planck = frame_.planck.data();
  job.sun_irradiance = frame_.sun_irradiance.data();
  job.output_node = request.output_node.data();
  job.rays = rays.data();
  job.radiance = result.radiance.data();
  job.transmittance = result.transmittance.data();
  job.attenuation = result.attenuation.data();
  job.cells = result.cells.data();
  if (items > 0)
    dispatch_march(job, [&](auto stride, auto kind) {
      for_items(items, threads_, [&](std::uint64_t item) {
        march_item<decltype(stride)::value, decltype(kind)::value>(job, item);
      });
    });
  times_ = {0.0, seconds_since(start)};
}

std::vector<float> HostExecutor::records(int node) const {
  return records_.at(static_cast<std::size_t>(node));
}

}  // namespace obscura
