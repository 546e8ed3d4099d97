#pragma once
// Writes a rendered sensor's images: one multi-channel OpenEXR per sensor
// (channels "<band>.radiance" W m⁻² sr⁻¹, "<band>.transmittance",
// "<band>.apparent_temperature" K) and PNG previews per band and quantity, each
// carrying the provenance record. Every file is written to a temporary name and
// renamed (nothing half-written).
#include <filesystem>
#include <string>
#include <vector>

#include "obscura/film/sensor_image.h"
#include "obscura/io/provenance.h"

namespace obscura {

// A band name made safe for file names ("8:12" → "8-12").
std::string file_safe_name(const std::string& name);

// Returns the paths written, EXR first. `suffix` is appended to every file
// name before its extension (frame numbers of a sequence: "_f0003").
std::vector<std::filesystem::path> write_sensor_image(const std::filesystem::path& dir,
                                                      const SensorImage& image,
                                                      const Provenance& provenance,
                                                      const std::string& suffix = "",
                                                      double time_s = 0.0);

// With the "envi" output: the sensor's band radiance (W m⁻² sr⁻¹) as one ENVI
// cube, <sensor><suffix>_radiance.img and .hdr (io/envi_cube.h), each band's
// centre and width being the midpoint and span of its response's limits.
// Returns the paths written.
std::vector<std::filesystem::path> write_sensor_radiance_cube(const std::filesystem::path& dir,
                                                              const SensorImage& image,
                                                              const std::string& suffix,
                                                              double time_s);

}  // namespace obscura
