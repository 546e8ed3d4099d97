#include "obscura/io/obj_mesh.h"

#include <fmt/format.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <istream>
#include <limits>
#include <streambuf>
#include <string_view>
#include <vector>

#include "obscura/core/error.h"
#include "obscura/io/text_lines.h"

namespace obscura {
namespace {

// The whitespace-separated tokens of a line, as tinyobjloader splits them.
std::vector<std::string_view> tokens(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (true) {
    i = s.find_first_not_of(" \t", i);
    if (i == std::string_view::npos) return out;
    const std::size_t e = std::min(s.find_first_of(" \t", i), s.size());
    out.push_back(s.substr(i, e - i));
    i = e;
  }
}

// A line's keyword ("v", "f", ...) when it is followed by a space or tab, and its arguments.
bool keyword_line(std::string_view line, char keyword, std::string_view& args) {
  line = line.substr(std::min(line.find_first_not_of(" \t"), line.size()));
  if (line.size() < 2 || line[0] != keyword || (line[1] != ' ' && line[1] != '\t')) return false;
  args = line.substr(2);
  return true;
}

// tinyobjloader reads an index with int arithmetic that wraps (99999999999999
// became 276447231): every index of a face corner ("v", "v/vt", "v//vn",
// "v/vt/vn") must be an integer within int's range before it sees them.
void check_face_corner(std::string_view corner, const std::string& file, const std::string& field) {
  std::size_t start = 0;
  while (start <= corner.size()) {
    const std::size_t slash = std::min(corner.find('/', start), corner.size());
    const std::string_view number = corner.substr(start, slash - start);
    if (!number.empty() || start == 0) {
      long long value = 0;
      const char* end = number.data() + number.size();
      const auto [ptr, ec] = std::from_chars(number.data(), end, value);
      if (ec == std::errc::result_out_of_range ||
          (ec == std::errc() && ptr == end &&
           (value > std::numeric_limits<int>::max() || value < -std::numeric_limits<int>::max())))
        throw InputError(file, field,
                         fmt::format("face index '{}' is out of range (at most {})", number,
                                     std::numeric_limits<int>::max()));
      if (number.empty() || ec != std::errc() || ptr != end)
        throw InputError(
            file, field,
            fmt::format("face corner '{}': index '{}' is not an integer", corner, number));
    }
    start = slash + 1;
  }
}

// tinyobjloader reads a coordinate that is not a number as 0 and ignores
// oversized files until memory runs out: one cheap pass first checks every
// vertex and counts the faces and triangles.
void prescan(const std::string& text, const std::string& file) {
  TextLines lines(text);
  std::string_view line, args;
  std::uint64_t vertices = 0, faces = 0, triangles = 0;
  while (lines.next(line)) {
    const std::string field = fmt::format("line {}", lines.number());
    if (keyword_line(line, 'v', args)) {
      const auto t = tokens(args);
      if (t.size() < 3) throw InputError(file, field, "a vertex needs three coordinates (v x y z)");
      if (++vertices > kMaxMeshVertices)
        throw InputError(file, field,
                         fmt::format("more than {} vertices: refused", kMaxMeshVertices));
      for (int k = 0; k < 3; ++k) {
        const auto v = parse_number(t[k]);
        if (!v)
          throw InputError(file, field,
                           fmt::format("vertex coordinate '{}' is not a number", t[k]));
        if (!std::isfinite(*v))
          throw InputError(file, field, fmt::format("vertex coordinate '{}' is not finite", t[k]));
      }
    } else if (keyword_line(line, 'f', args)) {
      const auto face = tokens(args);
      const std::size_t n = face.size();
      for (const std::string_view corner : face) check_face_corner(corner, file, field);
      if (n < 3)
        throw InputError(file, field,
                         fmt::format("a face needs at least 3 vertices, this one has {}", n));
      if (n > 255)
        throw InputError(
            file, field,
            fmt::format("a face has {} vertices, more than 255 (tinyobjloader's limit)", n));
      ++faces;
      triangles += n - 2;
      if (triangles > kMaxMeshTriangles)
        throw InputError(file, field,
                         fmt::format("more than {} triangles: refused", kMaxMeshTriangles));
    }
  }
  if (faces == 0)
    throw InputError(file, "", "no faces: the file has no triangles (is it an OBJ file?)");
}

// The line of the `index`-th face (0-based, in file order), for messages.
long long face_line(const std::string& text, std::uint64_t index) {
  TextLines lines(text);
  std::string_view line, args;
  std::uint64_t seen = 0;
  while (lines.next(line))
    if (keyword_line(line, 'f', args) && seen++ == index) return lines.number();
  return 0;
}

struct ParsedObj {
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
};

// Reads a string in place as a stream (an istringstream would copy it).
struct TextBuffer : std::streambuf {
  explicit TextBuffer(const std::string& text) {
    char* p = const_cast<char*>(text.data());  // only read: the get area
    setg(p, p, p + text.size());
  }
};

ParsedObj parse(const std::string& text, const std::string& file, bool triangulate) {
  ParsedObj p;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  TextBuffer buffer(text);
  std::istream in(&buffer);
  if (!tinyobj::LoadObj(&p.attrib, &p.shapes, &materials, &warn, &err, &in, nullptr, triangulate)) {
    while (!err.empty() && (err.back() == '\n' || err.back() == '.')) err.pop_back();
    throw InputError(file, "",
                     fmt::format("cannot parse the OBJ: {}", err.empty() ? "unknown error" : err));
  }
  return p;
}

// Every face's vertex indices must name a vertex: tinyobjloader only warns.
// Returns whether any face has more than 3 vertices.
bool check_indices(const ParsedObj& p, const std::string& text, const std::string& file) {
  const long long n = static_cast<long long>(p.attrib.vertices.size() / 3);
  std::uint64_t face = 0;
  bool polygons = false;
  for (const auto& shape : p.shapes) {
    std::size_t at = 0;
    for (const unsigned char count : shape.mesh.num_face_vertices) {
      polygons = polygons || count > 3;
      for (unsigned k = 0; k < count; ++k) {
        const long long vi = shape.mesh.indices[at + k].vertex_index;
        if (vi >= 0 && vi < n) continue;
        const std::string where = fmt::format("line {}", face_line(text, face));
        throw InputError(
            file, where,
            vi < 0 ? std::string("a relative vertex index points before the first vertex")
                   : fmt::format("vertex index {} is out of range: the file has {} vertices",
                                 vi + 1, n));
      }
      at += count;
      ++face;
    }
  }
  return polygons;
}

}  // namespace

TriangleMesh read_obj_mesh(const std::filesystem::path& path) {
  const std::string file = path.string();
  const std::string text = read_text_file(path, kMaxObjFileBytes, "OBJ mesh");
  prescan(text, file);
  ParsedObj obj = parse(text, file, false);
  // tinyobjloader triangulates polygons on a second parse, once every index is known to be valid.
  if (check_indices(obj, text, file)) obj = parse(text, file, true);

  TriangleMesh mesh;
  const auto& v = obj.attrib.vertices;
  mesh.vertices.reserve(v.size() / 3);
  for (std::size_t i = 0; i + 2 < v.size(); i += 3)
    mesh.vertices.emplace_back(v[i], v[i + 1], v[i + 2]);
  std::vector<std::uint64_t> faces_in_part;
  for (const auto& shape : obj.shapes) {
    if (shape.mesh.indices.empty()) continue;
    const std::string name = shape.name.empty() ? "default" : shape.name;
    int part = mesh.find_part(name);
    if (part < 0) {
      part = static_cast<int>(mesh.part_names.size());
      mesh.part_names.push_back(name);
      faces_in_part.push_back(0);
    }
    const auto& idx = shape.mesh.indices;
    for (std::size_t i = 0; i + 2 < idx.size(); i += 3) {
      ++faces_in_part[part];
      mesh.triangles.push_back({static_cast<std::uint32_t>(idx[i].vertex_index),
                                static_cast<std::uint32_t>(idx[i + 1].vertex_index),
                                static_cast<std::uint32_t>(idx[i + 2].vertex_index)});
      mesh.triangle_part.push_back(static_cast<std::uint32_t>(part));
      if (!(mesh.double_area(mesh.triangles.size() - 1) > 0)) {
        mesh.triangles.pop_back();
        mesh.triangle_part.pop_back();
      }
    }
  }
  std::vector<std::uint64_t> kept(mesh.part_names.size(), 0);
  for (const std::uint32_t p : mesh.triangle_part) ++kept[p];
  for (std::size_t p = 0; p < kept.size(); ++p)
    if (kept[p] == 0)
      throw InputError(file, "",
                       fmt::format("part '{}': all its {} triangles have zero area",
                                   mesh.part_names[p], faces_in_part[p]));
  if (mesh.triangles.empty()) throw InputError(file, "", "no triangles");
  return mesh;
}

}  // namespace obscura
