#pragma once
// A sensor: a camera that records several spectral bands at once.
#include <string>
#include <vector>

#include "obscura/core/band.h"
#include "obscura/scene/camera.h"

namespace obscura {

// The largest image side a scene may ask for, px.
inline constexpr int kMaxImageSide = 16384;

struct Sensor {
  std::string name;
  PinholeCamera camera;
  std::vector<Band> bands;
};

}  // namespace obscura
