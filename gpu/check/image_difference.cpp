#include "image_difference.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace obscura::gpu_check {

ImageDifference image_difference(const std::vector<double>& gpu, const std::vector<double>& cpu,
                                 const std::vector<bool>& where, double floor) {
  if (gpu.size() != cpu.size() || (!where.empty() && where.size() != cpu.size()))
    throw std::invalid_argument("images of different sizes");
  ImageDifference d;
  double largest = 0.0;
  for (const double v : cpu) largest = std::max(largest, std::abs(v));
  const double smallest = std::max(floor * largest, 1e-300);
  double sum = 0.0;
  for (std::size_t i = 0; i < cpu.size(); ++i) {
    const double r = std::abs(gpu[i] - cpu[i]) / std::max(std::abs(cpu[i]), smallest);
    if (where.empty() || where[i]) {
      sum += r;
      ++d.pixels;
    }
    if (!(r <= d.worst)) {  // NaN counts as the worst
      d.worst = std::isnan(r) ? INFINITY : r;
      d.worst_pixel = i;
    }
  }
  d.mean = d.pixels == 0 ? 0.0 : sum / static_cast<double>(d.pixels);
  return d;
}

}  // namespace obscura::gpu_check
