#include "obscura/gpu/lattice_executor.h"

#include <stdexcept>

namespace obscura {

std::uint64_t FrameLattice::bytes() const {
  const std::uint64_t record_bytes =
      (slot_count() + 1) * static_cast<std::uint64_t>(stride) * sizeof(float);
  return record_bytes * records.size() + (slot_count() + 1) +
         block_grid_size() * sizeof(std::int32_t) + block_count() * sizeof(std::array<int, 3>) +
         planck.size() * 4 * static_cast<std::uint64_t>(kMaxTableTemperatureK) * sizeof(double);
}

MarchJob make_march_job(const LatticeView& view, std::int32_t stride, int nodes,
                        const MarchRequest& request, std::uint64_t ray_count) {
  if (!march_supported(stride, request.source))
    throw std::invalid_argument("lattice march: no kernel for records of " +
                                std::to_string(stride) + " floats with this source");
  if (request.source == MarchSource::kCache && sh_degree_of_stride(stride) != request.sh_degree)
    throw std::invalid_argument("lattice march: records of " + std::to_string(stride) +
                                " floats do not hold degree " + std::to_string(request.sh_degree));
  for (const std::int32_t u : request.output_node)
    if (u < 0 || u >= nodes)
      throw std::invalid_argument("lattice march: output at spectral node " + std::to_string(u) +
                                  " of " + std::to_string(nodes));
  MarchJob job;
  job.lattice = view;
  job.ray_count = ray_count;
  job.outputs = static_cast<std::int32_t>(request.output_node.size());
  job.stride = stride;
  job.source = request.source;
  job.sh_degree = request.sh_degree;
  job.peak_channel = request.peak_channel;
  job.sun = request.sun ? 1 : 0;
  job.to_sun = request.to_sun;
  return job;
}

}  // namespace obscura
