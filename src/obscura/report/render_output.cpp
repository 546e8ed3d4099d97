#include "obscura/report/render_output.h"

#include <fmt/format.h>

#include "obscura/io/envi_cube.h"
#include "obscura/io/exr_writer.h"
#include "obscura/report/png_preview.h"

namespace obscura {

std::string file_safe_name(const std::string& name) {
  std::string out;
  for (char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '.' || c == '_' || c == '-';
    out += ok ? c : '-';
  }
  return out;
}

std::vector<std::filesystem::path> write_sensor_image(const std::filesystem::path& dir,
                                                      const SensorImage& image,
                                                      const Provenance& provenance,
                                                      const std::string& suffix, double time_s) {
  std::vector<std::filesystem::path> written;
  const std::string prov = provenance.to_string();
  std::vector<ExrChannel> channels;
  std::map<std::string, std::string> attributes = {{"obscura.provenance", prov},
                                                   {"obscura.sensor", image.sensor}};
  // Numbers as numeric attributes (docs/formats.md, "Render outputs").
  std::map<std::string, double> numbers = {{"obscura.time_s", time_s}};
  std::map<std::string, int> counts;
  for (const BandImage& b : image.bands) {
    const std::string n = b.band.name();
    channels.push_back({n + ".radiance", b.radiance});
    channels.push_back({n + ".transmittance", b.transmittance});
    channels.push_back({n + ".apparent_temperature", b.apparent_temperature});
    attributes["obscura.units." + n + ".radiance"] = "W m-2 sr-1";
    attributes["obscura.units." + n + ".transmittance"] = "1";
    attributes["obscura.units." + n + ".apparent_temperature"] = "K";
    if (!b.radiance_stderr.empty()) {
      channels.push_back({n + ".radiance_stderr", b.radiance_stderr});
      attributes["obscura.units." + n + ".radiance_stderr"] = "W m-2 sr-1";
    }
    numbers["obscura.band." + n + ".min_um"] = b.band.lo_um();
    numbers["obscura.band." + n + ".max_um"] = b.band.hi_um();
    counts["obscura.band." + n + ".response_points"] =
        static_cast<int>(b.band.response_table().size());
  }
  const auto exr = dir / (file_safe_name(image.sensor) + suffix + ".exr");
  write_exr(exr, image.width, image.height, channels, attributes, numbers, counts);
  written.push_back(exr);

  const std::map<std::string, std::string> text = {{"obscura.provenance", prov}};
  for (const BandImage& b : image.bands) {
    const std::string stem = file_safe_name(image.sensor) + "_" + file_safe_name(b.band.name());
    struct Quantity {
      const char* file_part;
      const char* title;
      const char* units;
      const std::vector<float>* values;
      Colormap map;
    };
    const Quantity quantities[] = {
        {"radiance", "band radiance", "W m⁻² sr⁻¹", &b.radiance, Colormap::kInferno},
        {"apparent_temperature", "apparent temperature", "K", &b.apparent_temperature,
         Colormap::kInferno},
        {"transmittance", "transmittance", "1", &b.transmittance, Colormap::kGray}};
    for (const Quantity& q : quantities) {
      PreviewOptions opt;
      opt.title = fmt::format("{} · {} ({}–{} µm) · {} · t = {:.4g} s", image.sensor, b.band.name(),
                              b.band.lo_um(), b.band.hi_um(), q.title, time_s);
      opt.units = q.units;
      opt.colormap = q.map;
      if (q.map == Colormap::kGray) {
        opt.min = 0.0;
        opt.max = 1.0;
      }
      const auto path = dir / (stem + "_" + q.file_part + suffix + ".png");
      write_png_preview(path, image.width, image.height, *q.values, opt, text);
      written.push_back(path);
    }
  }
  return written;
}

std::vector<std::filesystem::path> write_sensor_radiance_cube(const std::filesystem::path& dir,
                                                              const SensorImage& image,
                                                              const std::string& suffix,
                                                              double time_s) {
  EnviCube cube;
  cube.width = image.width;
  cube.height = image.height;
  cube.data_units = "W m-2 sr-1";
  cube.description =
      fmt::format("obscura band radiance, sensor {}, t = {:g} s", image.sensor, time_s);
  for (const BandImage& b : image.bands)
    cube.bands.push_back({b.band.name(), 0.5 * (b.band.lo_um() + b.band.hi_um()),
                          b.band.hi_um() - b.band.lo_um(), b.radiance.data()});
  const auto img = dir / (file_safe_name(image.sensor) + suffix + "_radiance.img");
  return write_envi_cube(img, cube);
}

}  // namespace obscura
