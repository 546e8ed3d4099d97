#pragma once
// ENVI image cubes (Harris Geospatial, "ENVI Header Format"): a raw
// band-sequential file of 32-bit little-endian floats (`.img`) and a text
// header beside it (`.hdr`) giving the size, the band names, the band centre
// wavelengths and widths (µm) and the data units, as image analysts' tools
// (ENVI, GDAL, QGIS, spectral Python) read them.
#include <filesystem>
#include <string>
#include <vector>

namespace obscura {

struct EnviBand {
  std::string name;
  double centre_um = 0;           // wavelength, µm
  double width_um = 0;            // full width, µm (the header's "fwhm")
  const float* values = nullptr;  // width × height, row-major, top row first
};

struct EnviCube {
  int width = 0, height = 0;
  std::vector<EnviBand> bands;
  std::string data_units;   // e.g. "W m-2 sr-1"
  std::string description;  // free text, one line
};

// Writes `img_path` and the header beside it (the same name with the
// extension .hdr), each under a temporary name and renamed when whole, and
// returns the two paths. Throws InputError on a cube without bands or
// pixels, Error on I/O failure.
std::vector<std::filesystem::path> write_envi_cube(const std::filesystem::path& img_path,
                                                   const EnviCube& cube);

// The header's text, for tests and docs.
std::string envi_header_text(const EnviCube& cube);

}  // namespace obscura
