#include "obscura/scene/output_formats.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>

#include "obscura/io/json_reader.h"

namespace obscura {
namespace {

struct FormatName {
  OutputFormat format;
  std::string_view name;
};
constexpr std::array kFormatNames = {FormatName{OutputFormat::kNetcdf, "netcdf"},
                                     FormatName{OutputFormat::kEnvi, "envi"}};

}  // namespace

std::string_view output_format_name(OutputFormat format) {
  for (const FormatName& f : kFormatNames)
    if (f.format == format) return f.name;
  return "?";
}

std::optional<OutputFormat> parse_output_format(std::string_view name) {
  for (const FormatName& f : kFormatNames)
    if (f.name == name) return f.format;
  return std::nullopt;
}

std::string unknown_output_format_message(std::string_view name) {
  std::string known;
  for (const FormatName& f : kFormatNames)
    known += (known.empty() ? "" : ", ") + std::string(f.name);
  return fmt::format(
      "unknown output format '{}' (expected: {}; EXR, PNG, CSV and JSON files are always "
      "written)",
      name, known);
}

void add_output_format(std::vector<OutputFormat>& formats, OutputFormat format) {
  if (!has_output_format(formats, format)) formats.push_back(format);
}

bool has_output_format(const std::vector<OutputFormat>& formats, OutputFormat format) {
  return std::find(formats.begin(), formats.end(), format) != formats.end();
}

std::vector<OutputFormat> parse_output_formats(JsonObject& root) {
  std::vector<OutputFormat> formats;
  if (!root.has("outputs")) return formats;
  const nlohmann::json& list = root.array("outputs");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string path = fmt::format("{}/{}", root.path_of("outputs"), i);
    if (!list[i].is_string())
      throw InputError(root.file(), path, "must be a format name (a string), e.g. \"netcdf\"");
    const std::string name = list[i].get<std::string>();
    const auto format = parse_output_format(name);
    if (!format) throw InputError(root.file(), path, unknown_output_format_message(name));
    add_output_format(formats, *format);
  }
  return formats;
}

}  // namespace obscura
