#pragma once
// An array in device memory that frees itself (cudaMalloc / cudaFree), with
// copies from and to the host. For .cu files only (cuda_runtime.h).
#include <cuda_runtime.h>

#include <cstddef>
#include <utility>
#include <vector>

#include "obscura/gpu/cuda/cuda_check.h"

namespace obscura {

template <class T>
class DeviceBuffer {
 public:
  DeviceBuffer() = default;
  explicit DeviceBuffer(std::size_t count) { resize(count); }
  DeviceBuffer(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(const DeviceBuffer&) = delete;
  DeviceBuffer(DeviceBuffer&& o) noexcept
      : data_(std::exchange(o.data_, nullptr)), size_(std::exchange(o.size_, 0)) {}
  DeviceBuffer& operator=(DeviceBuffer&& o) noexcept {
    std::swap(data_, o.data_);
    std::swap(size_, o.size_);
    return *this;
  }
  ~DeviceBuffer() {
    if (data_) cudaFree(data_);  // no throw from a destructor; a failure here frees nothing more
  }

  // Exactly `count` elements (contents undefined after a change of size).
  void resize(std::size_t count) {
    if (count == size_) return;
    if (data_) OBSCURA_CUDA(cudaFree(data_));
    data_ = nullptr;
    size_ = 0;
    if (count > 0) OBSCURA_CUDA(cudaMalloc(reinterpret_cast<void**>(&data_), count * sizeof(T)));
    size_ = count;
  }
  // At least `count` elements (kept when already as large: per-call scratch).
  void reserve(std::size_t count) {
    if (count > size_) resize(count);
  }
  void upload(const T* host, std::size_t count, cudaStream_t stream = nullptr) {
    reserve(count);
    if (count > 0)
      OBSCURA_CUDA(cudaMemcpyAsync(data_, host, count * sizeof(T), cudaMemcpyHostToDevice, stream));
  }
  void upload(const std::vector<T>& host, cudaStream_t stream = nullptr) {
    upload(host.data(), host.size(), stream);
  }
  void download(T* host, std::size_t count, cudaStream_t stream = nullptr) const {
    if (count > 0)
      OBSCURA_CUDA(cudaMemcpyAsync(host, data_, count * sizeof(T), cudaMemcpyDeviceToHost, stream));
  }

  T* data() const { return data_; }
  std::size_t size() const { return size_; }

 private:
  T* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace obscura
