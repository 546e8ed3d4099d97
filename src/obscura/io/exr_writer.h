#pragma once
// Radiance and auxiliary images as OpenEXR: one scanline part, 32-bit FLOAT
// channels (no half-float rounding of physical values), ZIP compression, and
// header attributes: text (provenance and units, by convention
// "obscura.provenance" and "obscura.units.<channel>") and numbers (64-bit
// double and 32-bit int attributes, e.g. "obscura.time_s"), so that a number
// is read back as a number, bit for bit.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace obscura {

struct ExrChannel {
  std::string name;           // e.g. "L" or "lwir.radiance"
  std::vector<float> pixels;  // width*height, row-major, top row first
};

// Writes through an AtomicFile, so `path` is either untouched or complete.
// Throws InputError for bad arguments (non-positive size, wrong pixel count,
// empty or duplicate channel names, an attribute name that is empty, reserved
// by OpenEXR or given twice) and Error if the file cannot be written.
void write_exr(const std::filesystem::path& path, int width, int height,
               const std::vector<ExrChannel>& channels,
               const std::map<std::string, std::string>& string_attributes,
               const std::map<std::string, double>& double_attributes = {},
               const std::map<std::string, int>& int_attributes = {});

struct ExrImage {
  int width = 0;
  int height = 0;
  // Every channel converted to float, width*height, row-major, top row first.
  std::map<std::string, std::vector<float>> channels;
  // The header's string attributes.
  std::map<std::string, std::string> string_attributes;
  // Its numeric attributes: double and float ones as double (OpenEXR's own
  // float attributes pixelAspectRatio and screenWindowWidth among them), int
  // ones as int. Other attribute types (OpenEXR's boxes, vectors, channel
  // list, compression, line order) are skipped.
  std::map<std::string, double> double_attributes;
  std::map<std::string, int> int_attributes;
};

// Reads any scanline or tiled single-part EXR. Throws InputError if the file
// cannot be opened or decoded.
ExrImage read_exr(const std::filesystem::path& path);

}  // namespace obscura
