#pragma once
// A rendered frame as bytes, so that the process that rendered it can hand it
// to rank 0, which measures and writes every frame (sequence_runner.h): each
// sensor's image, bit for bit, and its render statistics.
#include <string>

#include "obscura/scene/scene.h"
#include "obscura/sequence/sequence_runner.h"

namespace obscura {

std::string encode_frame(const RenderedFrame& frame);
// The frame back, its images shaped by `scene`'s sensors (the same scene the
// sender rendered). InternalError when the bytes do not fit that shape.
RenderedFrame decode_frame(const std::string& bytes, const Scene& scene);

}  // namespace obscura
