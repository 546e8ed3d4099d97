#pragma once
// The scenes of the photon-map study (issue #4; docs/validation.md): the puff
// of examples/puff-over-target (scripts/demo) in front of the hot box on the
// ground, seen by one camera in one narrow band, either
//  * visible: 0.55 µm, the puff scattering (albedo 0.9, g 0.6) in sunlight
//    (elevation 40°) under a uniform sky of 60 W m⁻² sr⁻¹ µm⁻¹ — multiple
//    scattering dominates; or
//  * lwir: 10 µm, the demo puff's coefficients (albedo 0.14, g 0.4, 12 K
//    warmer than the 288 K air) under a 250 K sky — emission dominates.
// Used by bench/photon_map_study_bench.cpp and the photon-map tests, so that
// both measure the same thing.
#include <string>

#include "obscura/scene/scene.h"

namespace obscura {

enum class StudyScene { kVisible, kLwir };

// The scene with one sensor ("cam") of width × height pixels and the given
// render method; the puff is voxelised at `resolution`³.
Scene make_study_scene(StudyScene which, int width, int height, RenderMethod method,
                       int resolution = 64);

}  // namespace obscura
