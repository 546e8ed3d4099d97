#pragma once
// CFD concentration fields from VTK legacy files (DATASET STRUCTURED_POINTS),
// ASCII or BINARY, and a writer for the same format. The format is VTK's
// "Simple Legacy Formats" (VTK User's Guide, "VTK File Formats", §"Simple
// Legacy Formats" and "Dataset Format: Structured Points"); the conventions
// obscura applies on top of it are in docs/formats.md, "CFD concentration
// import".
//
// Placement (a regular VTK grid mapped onto obscura's voxel convention,
// prep/concentration_series.h):
//  * POINT_DATA: point (i, j, k) lies at ORIGIN + SPACING·(i, j, k) and becomes
//    the voxel centred there, so the grid is DIMENSIONS voxels with
//    origin_m = ORIGIN − SPACING/2 and voxel_size_m = SPACING.
//  * CELL_DATA: cell (i, j, k) spans ORIGIN + SPACING·[(i, j, k), (i+1, j+1, k+1)]
//    and becomes that voxel: (nx−1)×(ny−1)×(nz−1) voxels, origin_m = ORIGIN.
//  * obscura voxels are cubes: the three SPACING components must agree to 1e−6
//    relative, otherwise the file is refused (resample it first).
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "obscura/medium/concentration_series.h"

namespace obscura {

// Which arrays of a VTK file make a ConcentrationFrame, and their units.
struct VtkArrayNames {
  // Name of the concentration array (a SCALARS array, or a 1-component FIELD
  // array inside POINT_DATA / CELL_DATA, as ParaView writes extra arrays).
  std::string concentration = "concentration";
  // Name of an optional temperature array (K, same POINT_DATA / CELL_DATA
  // section as the concentration); empty: the frame has no temperature.
  std::string temperature;
  // Factor from the file's concentration values to g/m³. VTK files carry no
  // units, so the values are taken as g/m³ unless the caller says otherwise
  // (kg/m³ → 1000, mg/m³ → 1e−3). Finite and > 0.
  double concentration_to_g_m3 = 1.0;
};

// Reads one VTK legacy STRUCTURED_POINTS file as the frame at `time_s`.
// Checks, in order: the header, the dataset keywords, that POINT_DATA /
// CELL_DATA counts match DIMENSIONS, that the grid fits in memory (before
// allocating), that binary data is not truncated (before allocating), then
// every value: concentration finite and ≥ 0, temperature finite and > 0.
// Throws InputError naming the file and the line (ASCII) or byte offset
// (BINARY), the array, or the voxel (i,j,k).
ConcentrationFrame read_vtk_structured_points(const std::filesystem::path& path, double time_s,
                                              const VtkArrayNames& names = {});

// Reads a time series, one VTK file per time: (time in s, path) pairs in
// strictly increasing time. Every frame must have the same grid (dims, origin
// and voxel size to 1e−9 voxel); a file whose grid differs is refused, since
// keyframe interpolation blends voxels one for one. Temperature is read from
// every file when names.temperature is set. Throws InputError.
ConcentrationSeries read_vtk_series(
    const std::vector<std::pair<double, std::string>>& time_and_path,
    const VtkArrayNames& names = {});

enum class VtkEncoding { kAscii, kBinary };

// Where the writer puts the voxel values: at VTK points (the voxel centres,
// DIMENSIONS = dims; what CFD codes usually write and how VTK interpolates),
// or in VTK cells (the voxels themselves, DIMENSIONS = dims + 1; origin and
// voxel size then round-trip bit for bit).
enum class VtkDataLocation { kPoints, kCells };

// One named array for the writer; `grid` must outlive the call.
struct VtkScalarArray {
  std::string name;
  const ScalarGrid* grid = nullptr;
};

// Writes the arrays as SCALARS (float, 1 component) of one STRUCTURED_POINTS
// dataset. All grids must share dims and placement, with identity rotation;
// names must be non-empty and distinct (spaces and '%' are written %-encoded,
// as VTK does). Values are written as they are: ASCII prints each float in the
// shortest form that reads back exactly, BINARY stores big-endian floats
// (the VTK legacy byte order). Written atomically (AtomicFile): the file is
// complete or absent. Throws InputError for bad arguments, Error on I/O failure.
void write_vtk_structured_points(const std::filesystem::path& path,
                                 const std::vector<VtkScalarArray>& arrays, VtkEncoding encoding,
                                 VtkDataLocation location = VtkDataLocation::kPoints);

// Writes a frame's concentration (g/m³) as "concentration" and, if present,
// its temperature (K) as "temperature".
void write_vtk_frame(const std::filesystem::path& path, const ConcentrationFrame& frame,
                     VtkEncoding encoding, VtkDataLocation location = VtkDataLocation::kPoints);

}  // namespace obscura
