#pragma once
// Comparing a band image with a reference image of the same scene.
#include <algorithm>
#include <cmath>

#include "obscura/film/sensor_image.h"

namespace obscura::testing {

// Relative RMSE of image a against reference b with the two images' own
// noise taken out: sqrt(max(0, mean((a − b)² − σa² − σb²))) / mean(b), the
// systematic part of the difference. Images of deterministic methods carry
// no standard errors (an empty radiance_stderr): theirs count as zero.
inline double systematic_rmse(const BandImage& a, const BandImage& b) {
  auto variance = [](const BandImage& image, std::size_t i) {
    return image.radiance_stderr.empty()
               ? 0.0
               : double(image.radiance_stderr[i]) * image.radiance_stderr[i];
  };
  double se = 0, mean = 0;
  for (std::size_t i = 0; i < a.radiance.size(); ++i) {
    const double d = a.radiance[i] - b.radiance[i];
    se += d * d - variance(a, i) - variance(b, i);
    mean += b.radiance[i];
  }
  const double n = a.radiance.size();
  return std::sqrt(std::max(0.0, se / n)) / (mean / n);
}

// Mean radiance of the image relative to the reference's, minus one.
inline double mean_error(const BandImage& a, const BandImage& b) {
  double sa = 0, sb = 0;
  for (std::size_t i = 0; i < a.radiance.size(); ++i) {
    sa += a.radiance[i];
    sb += b.radiance[i];
  }
  return sa / sb - 1.0;
}

}  // namespace obscura::testing
