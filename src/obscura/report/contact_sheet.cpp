#include "obscura/report/contact_sheet.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include "obscura/core/error.h"
#include "obscura/io/png_file.h"
#include "obscura/report/cairo_canvas.h"

namespace obscura {
namespace {

// Layout, px (font sizes in cairo user units = px on an image surface).
constexpr int kMargin = 12;
constexpr int kTitleGap = 8;    // title to the column headers
constexpr int kHeaderGap = 4;   // column headers to the first row
constexpr int kCellGap = 6;     // between columns and between rows
constexpr int kLabelGap = 12;   // row labels to the first column
constexpr int kLineGap = 2;     // between the lines of a row label
constexpr int kBarWidth = 100;  // the row's colour bar under its range
constexpr int kBarHeight = 8;
constexpr int kMinCellHeight = 8;
constexpr int kMaxSheetSize = 16384;
constexpr double kTitleFontSize = 16;
constexpr double kLabelFontSize = 13;
constexpr double kDetailFontSize = 12;
constexpr std::uint8_t kNanGrey = 128;

using cairo_canvas::CairoPtr;
using cairo_canvas::font_extents;
using cairo_canvas::set_font;
using cairo_canvas::SurfacePtr;
using cairo_canvas::text_advance;

// Source pixels (index, weight) that make up each of `n_out` pixels along an
// axis of `n_in`: the covered pixels weighted by overlap when shrinking, the
// nearest one when enlarging.
std::vector<std::vector<std::pair<int, double>>> axis_footprints(int n_in, int n_out) {
  std::vector<std::vector<std::pair<int, double>>> out(static_cast<std::size_t>(n_out));
  const double scale = static_cast<double>(n_in) / n_out;
  for (int i = 0; i < n_out; ++i) {
    if (n_out >= n_in) {
      out[i].push_back({std::min(n_in - 1, static_cast<int>((i + 0.5) * scale)), 1.0});
      continue;
    }
    const double a = i * scale, b = (i + 1) * scale;
    for (int k = static_cast<int>(std::floor(a));
         k < std::min(n_in, static_cast<int>(std::ceil(b))); ++k) {
      const double w = std::min(b, k + 1.0) - std::max(a, static_cast<double>(k));
      if (w > 0) out[i].push_back({k, w});
    }
  }
  return out;
}

std::string row_range_text(const ContactSheetRow& row, double lo, double hi) {
  const std::string range = fmt::format("{:.4g} – {:.4g}", lo, hi);
  return row.units.empty() ? range : range + " " + row.units;
}

void validate(const ContactSheet& sheet) {
  if (sheet.times_s.empty()) throw Error("contact sheet: no columns (frame times)");
  if (sheet.rows.empty()) throw Error("contact sheet: no rows");
  if (sheet.cell_height_px < kMinCellHeight || sheet.max_size_px < 64 ||
      sheet.max_size_px > kMaxSheetSize)
    throw Error(fmt::format(
        "contact sheet: cell height {} px (>= {}) or size cap {} px (64…{}) out of range",
        sheet.cell_height_px, kMinCellHeight, sheet.max_size_px, kMaxSheetSize));
  for (const ContactSheetRow& row : sheet.rows) {
    if (row.cells.size() != sheet.times_s.size())
      throw Error(fmt::format("contact sheet: row '{}' has {} cells for {} columns", row.label,
                              row.cells.size(), sheet.times_s.size()));
    int w = 0, h = 0;
    for (const ContactSheetCell& c : row.cells) {
      if (c.width == 0 && c.height == 0 && c.values.empty()) continue;  // blank
      if (c.width <= 0 || c.height <= 0 ||
          c.values.size() != static_cast<std::size_t>(c.width) * c.height)
        throw Error(fmt::format("contact sheet: row '{}': a {}x{} cell holds {} values", row.label,
                                c.width, c.height, c.values.size()));
      if (w != 0 && (c.width != w || c.height != h))
        throw Error(fmt::format("contact sheet: row '{}' mixes {}x{} and {}x{} cells", row.label, w,
                                h, c.width, c.height));
      w = c.width, h = c.height;
    }
  }
}

// The row's colour scale: as given, else the finite extremes of its cells.
std::pair<double, double> row_range(const ContactSheetRow& row) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const ContactSheetCell& c : row.cells)
    for (float v : c.values)
      if (std::isfinite(v))
        lo = std::min(lo, static_cast<double>(v)), hi = std::max(hi, static_cast<double>(v));
  if (!(lo <= hi)) lo = 0.0, hi = 1.0;  // no finite value
  if (row.min) lo = *row.min;
  if (row.max) hi = *row.max;
  if (!std::isfinite(lo) || !std::isfinite(hi) || lo > hi)
    throw Error(
        fmt::format("contact sheet: row '{}': invalid colour range [{}, {}]", row.label, lo, hi));
  return {lo, hi};
}

// The image size of a row's cells (0 × 0 when all are blank).
std::pair<int, int> row_image_size(const ContactSheetRow& row) {
  for (const ContactSheetCell& c : row.cells)
    if (c.width > 0) return {c.width, c.height};
  return {0, 0};
}

}  // namespace

std::vector<float> resample_image(int width, int height, const std::vector<float>& values,
                                  int new_width, int new_height) {
  if (width <= 0 || height <= 0 || new_width <= 0 || new_height <= 0 ||
      values.size() != static_cast<std::size_t>(width) * height)
    throw Error(fmt::format("resample: cannot resample {} values as {}x{} to {}x{}", values.size(),
                            width, height, new_width, new_height));
  const auto fx = axis_footprints(width, new_width), fy = axis_footprints(height, new_height);
  std::vector<float> out(static_cast<std::size_t>(new_width) * new_height);
  for (int y = 0; y < new_height; ++y)
    for (int x = 0; x < new_width; ++x) {
      double sum = 0, weight = 0;
      for (const auto& [sy, wy] : fy[y])
        for (const auto& [sx, wx] : fx[x]) {
          const float v = values[static_cast<std::size_t>(sy) * width + sx];
          if (!std::isfinite(v)) continue;
          sum += wx * wy * v;
          weight += wx * wy;
        }
      out[static_cast<std::size_t>(y) * new_width + x] =
          weight > 0 ? static_cast<float>(sum / weight) : std::numeric_limits<float>::quiet_NaN();
    }
  return out;
}

ContactSheetCell contact_sheet_thumbnail(int width, int height, const std::vector<float>& values,
                                         int max_side_px) {
  if (max_side_px < 1)
    throw Error(fmt::format("thumbnail: max side {} px must be >= 1", max_side_px));
  const double s = std::min(1.0, static_cast<double>(max_side_px) / std::max(width, height));
  ContactSheetCell c;
  c.width = std::max(1, static_cast<int>(std::lround(width * s)));
  c.height = std::max(1, static_cast<int>(std::lround(height * s)));
  c.values = (c.width == width && c.height == height)
                 ? values
                 : resample_image(width, height, values, c.width, c.height);
  return c;
}

std::vector<std::size_t> contact_sheet_frames(std::size_t frame_count, std::size_t max_columns) {
  std::vector<std::size_t> out;
  if (frame_count == 0 || max_columns == 0) return out;
  if (frame_count <= max_columns || max_columns == 1) {
    for (std::size_t i = 0; i < std::min(frame_count, max_columns); ++i) out.push_back(i);
    return out;
  }
  // Evenly spread, rounded to the nearest frame; the ends are exact.
  for (std::size_t k = 0; k < max_columns; ++k) {
    const std::size_t i = static_cast<std::size_t>(
        std::llround(static_cast<double>(k) * (frame_count - 1) / (max_columns - 1)));
    if (out.empty() || i != out.back()) out.push_back(i);
  }
  return out;
}

namespace {

// The sheet's texts and the sizes they need, measured on a scratch surface.
struct SheetText {
  cairo_font_extents_t title_font, label_font, detail_font;
  double title_w = 0;                // px; 0 without a title
  int title_h = 0;                   // px, with the gap below; 0 without a title
  std::vector<std::string> headers;  // "t = … s", per column
  double header_w = 0;               // widest header, px
  std::vector<std::string> ranges;   // colour range with units, per row
  int header_h = 0;                  // column headers with their gap, px
  int label_block_h = 0;             // a row's label, quantity, range and bar, px
  int label_col = 0;                 // the row labels' column with its gap, px
};

// Measures every text; fills in out.row_min and out.row_max (the colour
// ranges the range texts state).
SheetText measure_texts(const ContactSheet& sheet, ContactSheetRaster& out) {
  SheetText text;
  SurfacePtr scratch(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 1, 1));
  CairoPtr measure(cairo_create(scratch.get()));
  set_font(measure.get(), kTitleFontSize);
  text.title_font = font_extents(measure.get());
  text.title_w = sheet.title.empty() ? 0 : text_advance(measure.get(), sheet.title);
  text.title_h =
      sheet.title.empty() ? 0 : static_cast<int>(std::ceil(text.title_font.height)) + kTitleGap;
  set_font(measure.get(), kLabelFontSize);
  text.label_font = font_extents(measure.get());
  for (double t : sheet.times_s) {
    text.headers.push_back(fmt::format("t = {:.6g} s", t));
    text.header_w = std::max(text.header_w, text_advance(measure.get(), text.headers.back()));
  }
  double label_w = kBarWidth;
  for (const ContactSheetRow& row : sheet.rows)
    label_w = std::max(label_w, text_advance(measure.get(), row.label));
  set_font(measure.get(), kDetailFontSize);
  text.detail_font = font_extents(measure.get());
  for (const ContactSheetRow& row : sheet.rows) {
    const auto [lo, hi] = row_range(row);
    out.row_min.push_back(lo);
    out.row_max.push_back(hi);
    text.ranges.push_back(row_range_text(row, lo, hi));
    label_w = std::max({label_w, text_advance(measure.get(), row.quantity),
                        text_advance(measure.get(), text.ranges.back())});
  }
  text.header_h = static_cast<int>(std::ceil(text.label_font.height)) + kHeaderGap;
  text.label_block_h =
      static_cast<int>(std::ceil(text.label_font.height + 2 * text.detail_font.height)) +
      3 * kLineGap + kBarHeight;
  text.label_col = static_cast<int>(std::ceil(label_w)) + kLabelGap;
  return text;
}

// The largest cell height up to the requested one that keeps the sheet
// within the cap: sets the canvas size, cell height and widths and the cells'
// positions in `out`, and returns the column width, px.
int fit_cells(const ContactSheet& sheet, const SheetText& text, ContactSheetRaster& out) {
  const std::size_t rows = sheet.rows.size(), cols = sheet.times_s.size();
  std::vector<std::pair<int, int>> sizes;
  for (const ContactSheetRow& row : sheet.rows) sizes.push_back(row_image_size(row));
  int col_w = 0, row_h = 0;
  auto layout = [&](int h) {
    out.cell_widths.clear();
    col_w = static_cast<int>(std::ceil(text.header_w));
    for (const auto& [w, hh] : sizes) {
      const int cw =
          hh > 0 ? std::max(1, static_cast<int>(std::lround(static_cast<double>(w) * h / hh))) : 0;
      out.cell_widths.push_back(cw);
      col_w = std::max(col_w, cw);
    }
    row_h = std::max(h, text.label_block_h);
    out.width = std::max(
        2 * kMargin + text.label_col + static_cast<int>(cols) * (col_w + kCellGap) - kCellGap,
        2 * kMargin + static_cast<int>(std::ceil(text.title_w)));
    out.height = 2 * kMargin + text.title_h + text.header_h +
                 static_cast<int>(rows) * (row_h + kCellGap) - kCellGap;
    return out.width <= sheet.max_size_px && out.height <= sheet.max_size_px;
  };
  int h = sheet.cell_height_px;
  while (!layout(h)) {
    if (h == kMinCellHeight)
      throw Error(fmt::format(
          "contact sheet: {} rows × {} columns do not fit in {} px with cells {} px tall", rows,
          cols, sheet.max_size_px, kMinCellHeight));
    h = std::max(kMinCellHeight, static_cast<int>(h * 0.9));
  }
  out.cell_height = h;
  const int grid_x = kMargin + text.label_col, grid_y = kMargin + text.title_h + text.header_h;
  for (std::size_t c = 0; c < cols; ++c)
    out.cell_x.push_back(grid_x + static_cast<int>(c) * (col_w + kCellGap));
  for (std::size_t r = 0; r < rows; ++r)
    out.cell_y.push_back(grid_y + static_cast<int>(r) * (row_h + kCellGap));
  return col_w;
}

// Cells and colour bars straight into the surface (no filtering).
void paint_cells(cairo_surface_t* surface, const ContactSheet& sheet, const SheetText& text,
                 int col_w, const ContactSheetRaster& out) {
  const cairo_canvas::PixelWriter canvas(surface);
  const int h = out.cell_height;
  const int bar_y_offset =
      static_cast<int>(std::ceil(text.label_font.height + 2 * text.detail_font.height)) +
      3 * kLineGap;
  for (std::size_t r = 0; r < sheet.rows.size(); ++r) {
    const ContactSheetRow& row = sheet.rows[r];
    const double lo = out.row_min[r], span = out.row_max[r] - lo;
    const int cw = out.cell_widths[r];
    for (std::size_t c = 0; c < sheet.times_s.size(); ++c) {
      const ContactSheetCell& cell = row.cells[c];
      if (cell.width == 0) continue;
      const std::vector<float> pixels = resample_image(cell.width, cell.height, cell.values, cw, h);
      const int x0 = out.cell_x[c] + (col_w - cw) / 2, y0 = out.cell_y[r];
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < cw; ++x) {
          const float v = pixels[static_cast<std::size_t>(y) * cw + x];
          // A constant row (span 0) sits in the middle of the scale.
          const double t = span > 0 ? (v - lo) / span : 0.5;
          canvas.put(x0 + x, y0 + y,
                     std::isnan(v) ? std::array<std::uint8_t, 3>{kNanGrey, kNanGrey, kNanGrey}
                                   : colormap_rgb(row.colormap, t));
        }
    }
    for (int x = 0; x < kBarWidth; ++x) {
      const auto rgb = colormap_rgb(row.colormap, (x + 0.5) / kBarWidth);
      for (int y = 0; y < kBarHeight; ++y)
        canvas.put(kMargin + x, out.cell_y[r] + bar_y_offset + y, rgb);
    }
  }
  cairo_surface_mark_dirty(surface);
}

// The title, the column headers and each row's label, quantity and range.
void draw_texts(cairo_t* cr, const ContactSheet& sheet, const SheetText& text, int col_w,
                const ContactSheetRaster& out) {
  cairo_set_source_rgb(cr, 0, 0, 0);
  if (!sheet.title.empty()) {
    set_font(cr, kTitleFontSize);
    cairo_move_to(cr, kMargin, kMargin + text.title_font.ascent);
    cairo_show_text(cr, sheet.title.c_str());
  }
  set_font(cr, kLabelFontSize);
  for (std::size_t c = 0; c < sheet.times_s.size(); ++c) {
    const double w = text_advance(cr, text.headers[c]);
    cairo_move_to(cr, out.cell_x[c] + (col_w - w) / 2,
                  kMargin + text.title_h + text.label_font.ascent);
    cairo_show_text(cr, text.headers[c].c_str());
  }
  for (std::size_t r = 0; r < sheet.rows.size(); ++r) {
    double y = out.cell_y[r] + text.label_font.ascent;
    set_font(cr, kLabelFontSize);
    cairo_move_to(cr, kMargin, y);
    cairo_show_text(cr, sheet.rows[r].label.c_str());
    set_font(cr, kDetailFontSize);
    y += text.label_font.descent + kLineGap + text.detail_font.ascent;
    cairo_move_to(cr, kMargin, y);
    cairo_show_text(cr, sheet.rows[r].quantity.c_str());
    y += text.detail_font.height + kLineGap;
    cairo_move_to(cr, kMargin, y);
    cairo_show_text(cr, text.ranges[r].c_str());
  }
}

}  // namespace

ContactSheetRaster render_contact_sheet(const ContactSheet& sheet) {
  validate(sheet);
  ContactSheetRaster out;
  const SheetText text = measure_texts(sheet, out);
  const int col_w = fit_cells(sheet, text, out);
  SurfacePtr surface = cairo_canvas::create_surface(out.width, out.height, /*white=*/true);
  paint_cells(surface.get(), sheet, text, col_w, out);  // text after: on top
  CairoPtr cr(cairo_create(surface.get()));
  draw_texts(cr.get(), sheet, text, col_w, out);
  if (cairo_status(cr.get()) != CAIRO_STATUS_SUCCESS)
    throw Error(fmt::format("cairo: drawing the contact sheet failed: {}",
                            cairo_status_to_string(cairo_status(cr.get()))));
  cairo_surface_flush(surface.get());
  out.rgb = cairo_canvas::surface_rgb(surface.get());
  return out;
}

void write_contact_sheet_png(const std::filesystem::path& path, const ContactSheet& sheet,
                             const std::string& provenance_json) {
  if (provenance_json.find('\0') != std::string::npos)
    throw Error(fmt::format("cannot write PNG {}: provenance contains a NUL byte", path.string()));
  const ContactSheetRaster raster = render_contact_sheet(sheet);
  std::map<std::string, std::string> chunks;
  if (!provenance_json.empty()) chunks["obscura.provenance"] = provenance_json;
  write_rgb_png(path, raster.width, raster.height, raster.rgb, chunks);
}

}  // namespace obscura
