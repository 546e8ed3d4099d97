#include "obscura/scene/heightfield.h"

#include <fmt/format.h>

#include <cmath>

#include "obscura/core/error.h"
#include "obscura/io/text_lines.h"

namespace obscura {
namespace {

// 25 M samples of "-1234.567," fit well within this.
constexpr std::uintmax_t kMaxHeightfieldFileBytes = std::uintmax_t{1} << 30;

}  // namespace

Heightfield read_heightfield_csv(const std::filesystem::path& path) {
  const std::string file = path.string();
  const std::string text = read_text_file(path, kMaxHeightfieldFileBytes, "heightfield");
  Heightfield h;
  TextLines lines(text);
  std::string_view line;
  while (lines.next(line)) {
    const std::string_view row = trim(line);
    if (row.empty() || row.front() == '#') continue;
    std::size_t column = 0;
    std::size_t start = 0;
    while (true) {
      const std::size_t comma = row.find(',', start);
      const std::string_view field =
          trim(row.substr(start, comma == std::string_view::npos ? row.npos : comma - start));
      ++column;
      const std::string where = fmt::format("line {} column {}", lines.number(), column);
      const auto v = parse_number(field);
      if (field.empty()) throw InputError(file, where, "empty field: expected a height in metres");
      if (!v)
        throw InputError(file, where,
                         fmt::format("'{}' is not a number (expected a height in metres)", field));
      if (!std::isfinite(*v))
        throw InputError(file, where, fmt::format("'{}' is not a finite height", field));
      h.heights.push_back(*v);
      if (h.heights.size() > kMaxHeightfieldSamples)
        throw InputError(file, where,
                         fmt::format("more than {} samples: refused", kMaxHeightfieldSamples));
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    if (h.rows == 0)
      h.columns = column;
    else if (column != h.columns)
      throw InputError(
          file, fmt::format("line {}", lines.number()),
          fmt::format("{} values, but the first row has {} (rows must have equal lengths)", column,
                      h.columns));
    ++h.rows;
  }
  if (h.rows < 2 || h.columns < 2)
    throw InputError(
        file, "",
        fmt::format("{} rows of {} heights: a heightfield needs at least 2 x 2 samples", h.rows,
                    h.columns));
  return h;
}

TriangleMesh heightfield_mesh(const Heightfield& h, double origin_x, double origin_y,
                              double spacing_m, const std::string& part_name) {
  TriangleMesh m;
  m.part_names = {part_name};
  m.vertices.reserve(h.rows * h.columns);
  for (std::size_t i = 0; i < h.rows; ++i)
    for (std::size_t j = 0; j < h.columns; ++j)
      m.vertices.emplace_back(origin_x + static_cast<double>(j) * spacing_m,
                              origin_y + static_cast<double>(i) * spacing_m, h.at(i, j));
  m.triangles.reserve(2 * (h.rows - 1) * (h.columns - 1));
  for (std::size_t i = 0; i + 1 < h.rows; ++i)
    for (std::size_t j = 0; j + 1 < h.columns; ++j) {
      const auto a = static_cast<std::uint32_t>(i * h.columns + j);
      const auto b = a + 1;
      const auto d = static_cast<std::uint32_t>(a + h.columns);
      const auto c = d + 1;
      m.triangles.push_back({a, b, c});  // counter-clockwise seen from above: normal up
      m.triangles.push_back({a, c, d});
    }
  m.triangle_part.assign(m.triangles.size(), 0);
  return m;
}

}  // namespace obscura
