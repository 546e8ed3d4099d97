#pragma once
// The struct layout (gpu/struct_layout.h) as device code sees it, read by a
// one-thread kernel. Standard headers only. Throws CudaError.
#include <array>
#include <cstdint>

#include "obscura/gpu/struct_layout.h"

namespace obscura {

std::array<std::uint64_t, kStructLayoutValues> device_struct_layout();

}  // namespace obscura
