#pragma once
// How far the GPU's image is from the CPU's: per pixel |gpu − cpu| / |cpu|,
// where pixels whose CPU value is below `floor` × the image's largest count
// against that floor instead (empty sky reads 0 on both sides; its relative
// difference is meaningless); the worst over the image, and the mean over the
// pixels `where` marks (all when empty: an image that is mostly sky would
// otherwise dilute the mean with zeros).
#include <cstddef>
#include <vector>

namespace obscura::gpu_check {

struct ImageDifference {
  double mean = 0.0, worst = 0.0;
  std::size_t worst_pixel = 0;
  std::size_t pixels = 0;  // in the mean
};

ImageDifference image_difference(const std::vector<double>& gpu, const std::vector<double>& cpu,
                                 const std::vector<bool>& where = {}, double floor = 1e-6);

// Whether a difference meets the bar: mean ≤ 1e-4 and worst ≤ 1e-3.
inline bool agrees(const ImageDifference& d) { return d.mean <= 1e-4 && d.worst <= 1e-3; }

}  // namespace obscura::gpu_check
