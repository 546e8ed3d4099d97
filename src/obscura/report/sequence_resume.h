#pragma once
// Resuming a sequence that stopped part-way (`obscura render --resume`,
// docs/errors.md "Runs that lose nothing"): the frames a failed or
// interrupted run completed are read back from its folder instead of being
// rendered again, so the run goes on from the first missing frame and ends
// with the outputs an uninterrupted run writes (the frames' pixels, the time
// series and the metrics, bit for bit).
#include <cstddef>
#include <filesystem>
#include <vector>

#include "obscura/io/provenance.h"
#include "obscura/scene/scene.h"
#include "obscura/sequence/sequence_runner.h"

namespace obscura {

// The frames an earlier run in `dir` completed, from its summary.json: all of
// them after a complete run, "failed"/"frames_completed" after a failed or
// interrupted one, none when there is no summary (a fresh start). Throws
// InputError naming summary.json when that run was made from another scene,
// other input files (their SHA-256), another seed or other times.
std::vector<std::size_t> completed_frames(const std::filesystem::path& dir, const Scene& scene,
                                          const std::vector<double>& times_s,
                                          const Provenance& provenance);

// Frame `index` at `time_s` read back from its EXR files in `dir`: every
// sensor's radiance, transmittance, apparent temperature and standard error,
// as rendered. Its render statistics are not kept (zero). Throws InputError
// for a missing or unreadable file or one of another shape.
RenderedFrame read_completed_frame(const std::filesystem::path& dir, const Scene& scene,
                                   std::size_t index, double time_s);

}  // namespace obscura
