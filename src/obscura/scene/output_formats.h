#pragma once
// The optional output files of `obscura render`, beyond the EXR images, PNG
// previews, CSV and JSON files every render writes (docs/formats.md, "Render
// outputs"): named by the scene file's top-level "outputs" array and by the
// command line's --format, which add to each other.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace obscura {

enum class OutputFormat {
  kNetcdf,  // render.nc: every frame, sensor and band in one NetCDF-CF file
  kEnvi,    // <sensor>[_fNNNN]_radiance.img/.hdr: band radiance as an ENVI cube
};

// The name a scene file and the command line use ("netcdf").
std::string_view output_format_name(OutputFormat format);
// The format of that name; nothing for an unknown name.
std::optional<OutputFormat> parse_output_format(std::string_view name);
// "unknown output format 'x' (expected: netcdf; EXR, PNG, CSV and JSON files
// are always written)": the message for a name parse_output_format refuses.
std::string unknown_output_format_message(std::string_view name);

// Adds `format` to `formats` unless it is there already.
void add_output_format(std::vector<OutputFormat>& formats, OutputFormat format);
bool has_output_format(const std::vector<OutputFormat>& formats, OutputFormat format);

class JsonObject;
// The scene's "outputs" (an array of format names; absent: none). Errors name
// the JSON path of the element ("/outputs/1").
std::vector<OutputFormat> parse_output_formats(JsonObject& root);

}  // namespace obscura
