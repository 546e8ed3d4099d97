#pragma once
// A contact sheet: one PNG showing a frame sequence at a glance. Rows are
// images of one kind (a sensor's band and one quantity: radiance, apparent
// temperature or transmittance), columns are frame times. All cells of a row
// share one colour scale, so frames of a row compare directly; the row label
// gives the sensor/band, the quantity and the range with units, the column
// header the time. Numbers for analysis belong in the EXRs; like every PNG
// obscura writes, the sheet carries the provenance record.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "obscura/report/png_preview.h"

namespace obscura {

// One image of a row: `values` width × height, row-major, top row first (NaN
// drawn mid-grey). Keep it small: callers store thumbnails (see resample_image).
struct ContactSheetCell {
  int width = 0, height = 0;
  std::vector<float> values;
};

struct ContactSheetRow {
  std::string label;     // e.g. "ir / lwir"
  std::string quantity;  // e.g. "apparent temperature"
  std::string units;     // UTF-8, e.g. "K", "W m⁻² sr⁻¹"; empty for dimensionless
  Colormap colormap = Colormap::kInferno;
  // The colour scale; by default the finite minimum / maximum over the row's cells.
  std::optional<double> min, max;
  // One per column; a cell with no values (width 0) is left blank.
  std::vector<ContactSheetCell> cells;
};

struct ContactSheet {
  std::string title;            // may be empty
  std::vector<double> times_s;  // one per column, labelled "t = … s"
  std::vector<ContactSheetRow> rows;
  int cell_height_px = 160;  // cells are drawn this tall (aspect kept)...
  int max_size_px = 8192;    // ...smaller if the sheet would exceed this either way (<= 16384)
};

// The drawn sheet before PNG encoding (exposed for tests).
struct ContactSheetRaster {
  int width = 0, height = 0;      // canvas, px
  std::vector<std::uint8_t> rgb;  // 3 bytes per px, row-major, top row first
  int cell_height = 0;            // px, after any shrinking to fit max_size_px
  std::vector<int> cell_widths;   // px, per row
  // Top-left of cell (row r, column c) on the canvas: (cell_x[c], cell_y[r]).
  std::vector<int> cell_x, cell_y;
  std::vector<double> row_min, row_max;  // colour scale used per row
};

// Throws Error on no rows or no columns, a row with a cell count other than
// the column count, cells of one row with different sizes, a bad value count,
// an invalid range, or a sheet that cannot fit max_size_px with cells at
// least 8 px tall.
ContactSheetRaster render_contact_sheet(const ContactSheet& sheet);

// Draws and writes the sheet as an 8-bit RGB PNG through an AtomicFile; a
// non-empty `provenance_json` goes into the iTXt chunk "obscura.provenance".
void write_contact_sheet_png(const std::filesystem::path& path, const ContactSheet& sheet,
                             const std::string& provenance_json = "");

// `values` (width × height) resampled to new_width × new_height: the mean of
// the finite source pixels each target pixel covers (area-weighted) when
// shrinking, the nearest source pixel when enlarging. NaN where no finite
// pixel is covered.
std::vector<float> resample_image(int width, int height, const std::vector<float>& values,
                                  int new_width, int new_height);

// A cell of at most `max_side_px` either way (aspect kept, never enlarged):
// what a caller keeps per frame instead of the full image.
ContactSheetCell contact_sheet_thumbnail(int width, int height, const std::vector<float>& values,
                                         int max_side_px = 256);

// Which of `frame_count` frames a sheet of at most `max_columns` columns
// shows: all when they fit, else evenly spread, always the first and the last.
std::vector<std::size_t> contact_sheet_frames(std::size_t frame_count, std::size_t max_columns);

}  // namespace obscura
