#include <chrono>
#include <stdexcept>

#include "obscura/gpu/cuda/cuda_check.h"
#include "obscura/gpu/cuda/cuda_devices.h"
#include "obscura/gpu/cuda/cuda_executor.h"
#include "obscura/gpu/cuda/device_buffer.h"
#include "obscura/gpu/cuda/lattice_kernels.h"

namespace obscura {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A pair of events around the kernels of one call: their time on the device.
class KernelTimer {
 public:
  KernelTimer() {
    OBSCURA_CUDA(cudaEventCreate(&start_));
    OBSCURA_CUDA(cudaEventCreate(&stop_));
  }
  KernelTimer(const KernelTimer&) = delete;
  KernelTimer& operator=(const KernelTimer&) = delete;
  ~KernelTimer() {
    cudaEventDestroy(start_);
    cudaEventDestroy(stop_);
  }
  void start(cudaStream_t s) { OBSCURA_CUDA(cudaEventRecord(start_, s)); }
  void stop(cudaStream_t s) { OBSCURA_CUDA(cudaEventRecord(stop_, s)); }
  // After the stream has reached stop().
  double seconds() const {
    float ms = 0.0f;
    OBSCURA_CUDA(cudaEventElapsedTime(&ms, start_, stop_));
    return 1e-3 * ms;
  }

 private:
  cudaEvent_t start_ = nullptr, stop_ = nullptr;
};

}  // namespace

struct CudaExecutor::Device {
  int index = 0;
  std::string name;
  cudaStream_t stream = nullptr;
  KernelTimer timer;
  ExecutorTimes times;

  // The frame: its view and tables with device pointers.
  FrameLattice frame;
  DeviceBuffer<std::int32_t> block_index;
  DeviceBuffer<std::array<int, 3>> blocks;
  DeviceBuffer<std::uint8_t> occupied;
  std::vector<DeviceBuffer<float>> records;
  DeviceBuffer<float*> record_pointers;
  std::vector<DeviceBuffer<double>> planck_cubic;
  DeviceBuffer<PlanckTableView> planck;
  DeviceBuffer<double> sun_irradiance;

  // A march's scratch, kept between calls (grown as needed).
  DeviceBuffer<MarchRay> rays;
  DeviceBuffer<std::int32_t> output_node;
  DeviceBuffer<double> radiance, transmittance, attenuation;
  DeviceBuffer<std::uint32_t> cells;

  void synchronize() const { OBSCURA_CUDA(cudaStreamSynchronize(stream)); }
};

CudaExecutor::CudaExecutor(int device) : device_(std::make_unique<Device>()) {
  OBSCURA_CUDA(cudaSetDevice(device));
  device_->index = device;
  device_->name = cuda_device_info(device).name;
  OBSCURA_CUDA(cudaStreamCreateWithFlags(&device_->stream, cudaStreamNonBlocking));
}

CudaExecutor::~CudaExecutor() {
  if (device_ && device_->stream) cudaStreamDestroy(device_->stream);
}

std::string CudaExecutor::name() const {
  return "cuda:" + std::to_string(device_->index) + " (" + device_->name + ")";
}

ExecutorTimes CudaExecutor::last_times() const { return device_->times; }

void CudaExecutor::load(const FrameLattice& frame) {
  Device& d = *device_;
  const auto start = std::chrono::steady_clock::now();
  OBSCURA_CUDA(cudaSetDevice(d.index));
  const cudaStream_t s = d.stream;
  const LatticeView& v = frame.view;
  d.block_index.resize(frame.block_grid_size());
  d.block_index.upload(v.block_index, frame.block_grid_size(), s);
  d.blocks.resize(frame.block_count());
  d.blocks.upload(v.blocks, frame.block_count(), s);
  d.occupied.resize(frame.slot_count() + 1);
  d.occupied.upload(v.occupied, frame.slot_count() + 1, s);
  const std::size_t floats = (frame.slot_count() + 1) * static_cast<std::size_t>(frame.stride);
  d.records.resize(frame.records.size());
  std::vector<float*> pointers;
  for (std::size_t u = 0; u < frame.records.size(); ++u) {
    d.records[u].resize(floats);
    d.records[u].upload(frame.records[u], floats, s);
    pointers.push_back(d.records[u].data());
  }
  d.record_pointers.resize(pointers.size());
  d.record_pointers.upload(pointers, s);
  constexpr std::size_t kCoefficients = 4 * static_cast<std::size_t>(kMaxTableTemperatureK);
  d.planck_cubic.resize(frame.planck.size());
  std::vector<PlanckTableView> planck = frame.planck;
  for (std::size_t u = 0; u < planck.size(); ++u) {
    d.planck_cubic[u].resize(kCoefficients);
    d.planck_cubic[u].upload(planck[u].cubic, kCoefficients, s);
    planck[u].cubic = d.planck_cubic[u].data();
  }
  d.planck.resize(planck.size());
  d.planck.upload(planck, s);
  d.sun_irradiance.resize(frame.sun_irradiance.size());
  d.sun_irradiance.upload(frame.sun_irradiance, s);
  d.synchronize();  // the host arrays may go once load() returns

  d.frame = frame;
  d.frame.view.block_index = d.block_index.data();
  d.frame.view.blocks = d.blocks.data();
  d.frame.view.occupied = d.occupied.data();
  d.frame.records.assign(pointers.begin(), pointers.end());
  d.frame.planck = planck;
  d.times = {seconds_since(start), 0.0};
}

void CudaExecutor::sun_depths(const Vec3& to_sun) {
  Device& d = *device_;
  if (sh_degree_of_stride(d.frame.stride) < 0)
    throw std::invalid_argument("sun depths: the records hold no light");
  OBSCURA_CUDA(cudaSetDevice(d.index));
  SunDepthJob job;
  job.lattice = d.frame.view;
  job.records = d.record_pointers.data();
  job.slot_count = d.frame.slot_count();
  job.nodes = d.frame.nodes();
  job.stride = d.frame.stride;
  job.to_sun_lattice = d.frame.view.to_lattice_direction(to_sun);
  d.timer.start(d.stream);
  launch_sun_depths(job, d.stream);
  d.timer.stop(d.stream);
  d.synchronize();
  OBSCURA_CUDA(cudaGetLastError());
  d.times = {0.0, d.timer.seconds()};
}

void CudaExecutor::march(const MarchRequest& request, std::span<const MarchRay> rays,
                         MarchResult& result) {
  Device& d = *device_;
  OBSCURA_CUDA(cudaSetDevice(d.index));
  const auto start = std::chrono::steady_clock::now();
  MarchJob job =
      make_march_job(d.frame.view, d.frame.stride, d.frame.nodes(), request, rays.size());
  const std::uint64_t items = job.items();
  result.radiance.resize(items);
  result.transmittance.resize(items);
  result.attenuation.resize(items);
  result.cells.resize(items);
  if (items == 0) {
    d.times = {};
    return;
  }
  const cudaStream_t s = d.stream;
  d.rays.upload(rays.data(), rays.size(), s);
  d.output_node.upload(request.output_node, s);
  d.radiance.reserve(items);
  d.transmittance.reserve(items);
  d.attenuation.reserve(items);
  d.cells.reserve(items);
  job.records = d.record_pointers.data();
  job.planck = d.planck.data();
  job.sun_irradiance = d.sun_irradiance.data();
  job.output_node = d.output_node.data();
  job.rays = d.rays.data();
  job.radiance = d.radiance.data();
  job.transmittance = d.transmittance.data();
  job.attenuation = d.attenuation.data();
  job.cells = d.cells.data();
  d.timer.start(s);
  launch_march(job, s);
  d.timer.stop(s);
  d.radiance.download(result.radiance.data(), items, s);
  d.transmittance.download(result.transmittance.data(), items, s);
  d.attenuation.download(result.attenuation.data(), items, s);
  d.cells.download(result.cells.data(), items, s);
  d.synchronize();
  OBSCURA_CUDA(cudaGetLastError());
  const double kernel = d.timer.seconds();
  d.times = {seconds_since(start) - kernel, kernel};
}

std::vector<float> CudaExecutor::records(int node) const {
  const Device& d = *device_;
  OBSCURA_CUDA(cudaSetDevice(d.index));
  const DeviceBuffer<float>& r = d.records.at(static_cast<std::size_t>(node));
  std::vector<float> out(r.size());
  r.download(out.data(), out.size(), d.stream);
  d.synchronize();
  return out;
}

}  // namespace obscura
