#include "obscura/report/line_plot.h"

#include <fmt/format.h>

#include <map>
#include <tuple>

#include "obscura/core/error.h"
#include "obscura/io/png_file.h"
#include "obscura/report/cairo_canvas.h"
#include "obscura/report/line_plot_drawing.h"
#include "obscura/report/line_plot_layout.h"
#include "obscura/report/line_plot_style.h"

namespace obscura {

std::array<std::uint8_t, 3> plot_series_rgb(std::size_t index) {
  return line_plot::kPalette[index % std::size(line_plot::kPalette)];
}

LinePlotRaster render_line_plot(const LinePlot& plot) {
  line_plot::validate(plot);
  LinePlotRaster out;
  out.width = plot.width_px;
  out.height = plot.height_px;
  std::tie(out.x_min, out.x_max) = line_plot::axis_range(plot, /*is_x=*/true);
  std::tie(out.y_min, out.y_max) = line_plot::axis_range(plot, /*is_x=*/false);

  cairo_canvas::SurfacePtr surface = cairo_canvas::create_surface(out.width, out.height);
  cairo_canvas::CairoPtr owner(cairo_create(surface.get()));
  cairo_t* cr = owner.get();
  const line_plot::PlotLayout layout = line_plot::lay_out_line_plot(cr, plot, out);
  line_plot::draw_line_plot(cr, plot, layout, out);
  if (cairo_status(cr) != CAIRO_STATUS_SUCCESS) {
    throw Error(fmt::format("cairo: drawing the line plot failed: {}",
                            cairo_status_to_string(cairo_status(cr))));
  }
  cairo_surface_flush(surface.get());
  out.rgb = cairo_canvas::surface_rgb(surface.get());
  return out;
}

void write_line_plot_png(const std::filesystem::path& path, const LinePlot& plot,
                         const std::string& provenance_json) {
  const std::string file = path.string();
  if (provenance_json.find('\0') != std::string::npos) {
    throw Error(fmt::format("cannot write PNG {}: provenance contains a NUL byte", file));
  }
  const LinePlotRaster raster = render_line_plot(plot);

  std::map<std::string, std::string> chunks;
  if (!provenance_json.empty()) chunks["obscura.provenance"] = provenance_json;
  write_rgb_png(path, raster.width, raster.height, raster.rgb, chunks);
}

}  // namespace obscura
