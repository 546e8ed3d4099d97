// Finding materials (optics/material.h): by name or path, the shipped ones,
// and the sources a material cites.
#include <fmt/format.h>

#include <algorithm>

#include "obscura/core/data_directory.h"
#include "obscura/core/error.h"
#include "obscura/optics/material.h"

namespace obscura {

const char* to_string(MaterialKind kind) {
  switch (kind) {
    case MaterialKind::mie:
      return "mie";
    case MaterialKind::tabulated:
      return "tabulated";
    case MaterialKind::thin_flake:
      return "thin-flake";
  }
  return "?";
}

Material load_material_by_name(const std::string& name_or_path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (name_or_path.empty()) throw InputError("", "material", "no material named");
  const bool looks_like_path =
      name_or_path.find('/') != std::string::npos || fs::path(name_or_path).extension() == ".json";
  if (looks_like_path || fs::is_regular_file(name_or_path, ec)) return load_material(name_or_path);
  const fs::path shipped = data_directory() / "materials" / (name_or_path + ".json");
  const fs::path local = fs::current_path() / (name_or_path + ".json");
  for (const auto& p : {shipped, local})
    if (fs::is_regular_file(p, ec)) return load_material(p);
  throw InputError("", "material",
                   fmt::format("no material '{}': looked for {} and {} (obscura optics --list "
                               "shows the shipped ones)",
                               name_or_path, shipped.string(), local.string()));
}

std::vector<MaterialEntry> list_materials() {
  namespace fs = std::filesystem;
  const fs::path dir = data_directory() / "materials";
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw InputError(dir.string(), "", "the materials folder does not exist");
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && e.path().extension() == ".json") files.push_back(e.path());
  std::vector<MaterialEntry> out;
  for (const auto& f : files) {
    const Material m = load_material(f);
    out.push_back({m.name, m.description, to_string(m.kind), f});
  }
  std::sort(out.begin(), out.end(),
            [](const MaterialEntry& a, const MaterialEntry& b) { return a.name < b.name; });
  return out;
}

std::vector<std::pair<std::string, std::string>> material_sources(const Material& m) {
  std::vector<std::pair<std::string, std::string>> out;
  if (m.mie) {
    out.emplace_back("refractive index", m.mie->index.source);
    out.emplace_back("density", m.mie->density_source);
    out.emplace_back("size distribution", m.mie->distribution_source);
    if (m.mie->humidity) {
      out.emplace_back("humidity growth", m.mie->humidity->source);
      out.emplace_back("water refractive index", m.mie->humidity->water_index.source);
    }
  }
  if (m.flake) {
    out.emplace_back("flake", m.flake->source);
    if (m.flake->index) out.emplace_back("refractive index", m.flake->index->source);
  }
  if (m.tabulated) {
    for (const auto& b : m.tabulated->bands)
      out.emplace_back(b.lo_um == b.hi_um ? fmt::format("tabulated {} µm", b.lo_um)
                                          : fmt::format("tabulated {}–{} µm", b.lo_um, b.hi_um),
                       b.source);
  }
  return out;
}

}  // namespace obscura
