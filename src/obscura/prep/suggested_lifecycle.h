#pragma once
// A lifecycle for prepared keyframes (docs/time-varying-clouds.md), suggested
// from the source's timing as the source paper plays its smoke:
//  * initialisation while the devices burn: keyframes up to the last one at or
//    before the end of burning (e);
//  * evolution: a loop over the first half of the keyframes after it
//    (a = e … b), wrapping back over one keyframe interval;
//  * extinction: the rest (x = b + 1 … n − 1), the cloud dispersing.
// Without a burn time (CFD input) the initialisation is the first keyframe.
#include <optional>
#include <vector>

#include "obscura/medium/lifecycle.h"

namespace obscura {

// Needs at least two keyframe times (the extinction needs a keyframe after the
// loop); throws InputError otherwise.
LifecycleSpec suggest_lifecycle(const std::vector<double>& keyframe_times_s,
                                std::optional<double> burn_end_s);

}  // namespace obscura
