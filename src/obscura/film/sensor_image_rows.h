#pragma once
// A share of a SensorImage's rows as bytes, for the processes of a run to
// send one another (core/process_group.h): rows y with y mod stride = offset,
// every per-pixel array, and the render counters. Decoding writes those rows
// into an image of the same shape, so the shares of every process make the
// whole image, bit for bit.
#include <string>

#include "obscura/film/sensor_image.h"

namespace obscura {

std::string encode_image_rows(const SensorImage& image, int row_offset = 0, int row_stride = 1);

// Writes the rows `bytes` holds into `image` (same width, height, bands and
// standard-error images, else InternalError) and adds its counters (rays,
// segments, evaluations) to image.stats; the other statistics stay image's.
void decode_image_rows(const std::string& bytes, SensorImage& image);

}  // namespace obscura
