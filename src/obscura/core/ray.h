#pragma once
// A ray o + t d. Integrators keep d unit length so that t is a distance in metres.
#include "obscura/core/vec3.h"

namespace obscura {

struct Ray {
  Vec3 origin;
  Vec3 direction;  // unit length by convention
  Vec3 at(double t) const { return origin + direction * t; }
};

}  // namespace obscura
