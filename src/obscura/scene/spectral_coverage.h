#pragma once
// Whether the clouds' spectral samples cover the sensors' bands. Between
// samples a cloud's coefficients are interpolated linearly in wavelength;
// beyond the first and last they are held at that sample's values
// (render/spectral_nodes.h), which is right for a grey cloud and a guess for
// any other: a visible band through a cloud sampled only at 4 and 10 µm sees
// the 4 µm extinction. A band wholly outside the samples is worth a warning,
// not an error; one that overlaps them is not (a sample per band, such as
// 0.55 µm for the visible, is the usual way to prepare a cloud).
#include <string>
#include <vector>

#include "obscura/scene/scene.h"

namespace obscura {

// One line per sensor band wholly outside the staged medium's samples
// ("sensor ir, band visible (0.4-0.7 µm) lies outside the clouds' spectral
// samples (4-10 µm): ..."); none when no cloud is staged or the clouds have
// a single (grey) sample.
std::vector<std::string> bands_beyond_cloud_samples(const Scene& scene);

}  // namespace obscura
