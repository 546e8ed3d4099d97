// Reading a material file (optics/material.h, docs/materials.md): the JSON
// of each kind of material, checked value by value with errors naming the
// JSON path.
#include <fmt/format.h>

#include <cmath>
#include <functional>

#include "obscura/core/error.h"
#include "obscura/io/json_reader.h"
#include "obscura/optics/material.h"

namespace obscura {
namespace {

std::string element_path(const JsonObject& o, const std::string& key, std::size_t i) {
  return fmt::format("{}/{}", o.path_of(key), i);
}

std::string required_text(JsonObject& o, const std::string& key, const char* what) {
  std::string s = o.string(key);
  if (s.find_first_not_of(" \t\n") == std::string::npos) throw o.error(key, what);
  return s;
}

std::string source_of(JsonObject& o) {
  return required_text(o, "source", "must name the source of the values (it is empty)");
}

// A constraint on a number: a predicate and its wording for messages.
struct Bound {
  std::function<bool(double)> ok;
  const char* wording;
};
const Bound kPositive{[](double x) { return x > 0; }, "> 0"};
const Bound kUnit{[](double x) { return x >= 0 && x <= 1; }, "in [0, 1]"};
const Bound kFraction{[](double x) { return x > 0 && x <= 1; }, "in (0, 1]"};
const Bound kCosine{[](double x) { return x >= -1 && x <= 1; }, "in [-1, 1]"};

double bounded(JsonObject& o, const std::string& key, const Bound& bound) {
  const double x = o.number(key);
  if (!bound.ok(x)) throw o.error(key, fmt::format("must be {}, found {}", bound.wording, x));
  return x;
}

// A number, or {"min", "max"} (nominal: the midpoint), or {"value", "min", "max"}.
CitedValue cited(JsonObject& o, const std::string& key, const Bound& bound) {
  const auto& raw = o.raw(key);
  if (raw.is_number()) {
    const double x = bounded(o, key, bound);
    return {x, x, x};
  }
  if (!raw.is_object())
    throw o.error(key, "expected a number or an object {\"min\", \"max\"} (optionally \"value\")");
  JsonObject r = o.object(key);
  CitedValue v;
  v.min = bounded(r, "min", bound);
  v.max = bounded(r, "max", bound);
  if (v.min > v.max) throw r.error("max", fmt::format("max {} is below min {}", v.max, v.min));
  v.value = r.has("value") ? bounded(r, "value", bound) : 0.5 * (v.min + v.max);
  if (v.value < v.min || v.value > v.max)
    throw r.error("value",
                  fmt::format("{} lies outside [min, max] = [{}, {}]", v.value, v.min, v.max));
  r.finish();
  return v;
}

RefractiveIndexTable parse_index_table(JsonObject o) {
  RefractiveIndexTable t;
  t.source = source_of(o);
  const std::string key = "wavelength_um_n_k";
  const auto& rows = o.array(key);
  if (rows.size() < 2) throw o.error(key, "a table needs at least two rows [wavelength_um, n, k]");
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::string row_path = element_path(o, key, i);
    const auto& row = rows[i];
    if (!row.is_array() || row.size() != 3 || !row[0].is_number() || !row[1].is_number() ||
        !row[2].is_number())
      throw InputError(o.file(), row_path, "expected a row [wavelength_um, n, k] of three numbers");
    const double lambda = row[0].get<double>(), n = row[1].get<double>(), k = row[2].get<double>();
    if (!std::isfinite(lambda) || !(lambda > 0))
      throw InputError(o.file(), row_path + "/0",
                       fmt::format("wavelength must be > 0 µm, found {}", lambda));
    if (!t.wavelength_um.empty() && !(lambda > t.wavelength_um.back()))
      throw InputError(o.file(), row_path + "/0",
                       fmt::format("wavelengths must increase: {} µm follows {} µm", lambda,
                                   t.wavelength_um.back()));
    if (!std::isfinite(n) || !(n > 0))
      throw InputError(o.file(), row_path + "/1", fmt::format("n must be > 0, found {}", n));
    if (!std::isfinite(k) || !(k >= 0))
      throw InputError(o.file(), row_path + "/2",
                       fmt::format("k must be >= 0 (k >= 0 is absorbing), found {}", k));
    t.wavelength_um.push_back(lambda);
    t.n.push_back(n);
    t.k.push_back(k);
  }
  o.finish();
  return t;
}

LognormalDistribution parse_distribution(JsonObject o, std::string& source) {
  source = source_of(o);
  const std::string type = o.string("type");
  if (type != "lognormal")
    throw o.error("type",
                  fmt::format("unknown size distribution '{}' (expected \"lognormal\")", type));
  const double sigma = o.number("geometric_std");
  if (!(sigma > 1)) throw o.error("geometric_std", fmt::format("must be > 1, found {}", sigma));
  const bool mmd = o.has("mass_median_diameter_um"), cmr = o.has("count_median_radius_um");
  if (mmd == cmr)
    throw o.error("mass_median_diameter_um",
                  "give exactly one of mass_median_diameter_um and count_median_radius_um");
  LognormalDistribution d;
  if (mmd)
    d = LognormalDistribution::from_mass_median_diameter(
        bounded(o, "mass_median_diameter_um", kPositive), sigma);
  else
    d = {bounded(o, "count_median_radius_um", kPositive), sigma};
  o.finish();
  return d;
}

TabulatedOptics parse_tabulated(JsonObject o) {
  TabulatedOptics t;
  t.note = required_text(o, "note", "must say where the values come from (it is empty)");
  const auto& bands = o.array("bands");
  if (bands.empty()) throw o.error("bands", "give at least one band");
  for (std::size_t i = 0; i < bands.size(); ++i) {
    JsonObject b(bands[i], o.file(), element_path(o, "bands", i));
    TabulatedBand band;
    const auto& w = b.raw("wavelength_um");
    if (w.is_number()) {
      band.lo_um = band.hi_um = bounded(b, "wavelength_um", kPositive);
    } else {
      const auto range = b.numbers("wavelength_um");
      if (range.size() != 2 || !(range[0] > 0) || !(range[1] >= range[0]))
        throw b.error("wavelength_um",
                      "expected a wavelength > 0 or a band [lo, hi] with 0 < lo <= hi");
      band.lo_um = range[0];
      band.hi_um = range[1];
    }
    if (!t.bands.empty() && !(band.lo_um > t.bands.back().hi_um))
      throw b.error(
          "wavelength_um",
          fmt::format("bands must increase without overlapping: {} µm is not beyond {} µm",
                      band.lo_um, t.bands.back().hi_um));
    band.mass_extinction_m2_g = cited(b, "mass_extinction_m2_g", kPositive);
    if (b.has("albedo")) band.albedo = cited(b, "albedo", kUnit);
    if (b.has("asymmetry")) band.asymmetry = cited(b, "asymmetry", kCosine);
    band.source = source_of(b);
    band.note = b.string_or("note", "");
    b.finish();
    t.bands.push_back(std::move(band));
  }
  o.finish();
  return t;
}

HumidityGrowth parse_humidity(JsonObject o, const RefractiveIndexTable& index) {
  HumidityGrowth h;
  h.source = source_of(o);
  const std::string model = o.string("model");
  if (model != "raoult")
    throw o.error("model", fmt::format("unknown humidity model '{}' (expected \"raoult\")", model));
  h.reference_solute_mass_fraction = bounded(o, "reference_solute_mass_fraction", kFraction);
  h.solute_molar_mass_g_mol = bounded(o, "solute_molar_mass_g_mol", kPositive);
  h.water_molar_mass_g_mol = bounded(o, "water_molar_mass_g_mol", kPositive);
  h.van_t_hoff_factor = bounded(o, "van_t_hoff_factor", kPositive);
  h.water_density_g_cm3 = bounded(o, "water_density_g_cm3", kPositive);
  h.water_index = parse_index_table(o.object("water_refractive_index"));
  if (h.water_index.wavelength_um.front() > index.wavelength_um.front() ||
      h.water_index.wavelength_um.back() < index.wavelength_um.back())
    throw o.error(
        "water_refractive_index",
        fmt::format("covers {}–{} µm, less than the material's index table ({}–{} µm)",
                    h.water_index.wavelength_um.front(), h.water_index.wavelength_um.back(),
                    index.wavelength_um.front(), index.wavelength_um.back()));
  o.finish();
  return h;
}

MieModel parse_mie(JsonObject& root) {
  MieModel m;
  m.index = parse_index_table(root.object("refractive_index"));
  JsonObject density = root.object("density_g_cm3");
  m.density_g_cm3 = bounded(density, "value", kPositive);
  m.density_source = source_of(density);
  density.finish();
  m.distribution = parse_distribution(root.object("size_distribution"), m.distribution_source);
  if (auto h = root.optional_object("humidity_growth")) m.humidity = parse_humidity(*h, m.index);
  return m;
}

ThinFlakeModel parse_flake(JsonObject o) {
  ThinFlakeModel f;
  f.thickness_um = cited(o, "thickness_um", kPositive);
  f.density_g_cm3 = bounded(o, "density_g_cm3", kPositive);
  if (o.has("diameter_um")) f.diameter_um = cited(o, "diameter_um", kPositive);
  if (auto t = o.optional_object("refractive_index")) f.index = parse_index_table(*t);
  f.source = source_of(o);
  o.finish();
  return f;
}

}  // namespace

Material load_material(const std::filesystem::path& file) {
  const std::string name = file.string();
  const nlohmann::json doc = read_json_file(name);
  JsonObject root(doc, name, "");
  Material m;
  m.file = name;
  m.name = required_text(root, "name", "must not be empty");
  m.description = required_text(root, "description", "must not be empty");
  m.mass_basis = required_text(root, "mass_basis", "must say what one gram of the material is");
  const std::string kind = root.string("kind");
  if (root.has("notes")) {
    const auto& notes = root.array("notes");
    for (std::size_t i = 0; i < notes.size(); ++i) {
      if (!notes[i].is_string())
        throw InputError(name, element_path(root, "notes", i), "expected a string");
      m.notes.push_back(notes[i].get<std::string>());
    }
  }
  if (kind == "mie") {
    m.kind = MaterialKind::mie;
    m.mie = parse_mie(root);
    if (auto t = root.optional_object("tabulated")) {
      m.tabulated = parse_tabulated(*t);
      const auto& w = m.mie->index.wavelength_um;
      for (std::size_t i = 0; i < m.tabulated->bands.size(); ++i) {
        const auto& b = m.tabulated->bands[i];
        if (b.hi_um >= w.front() && b.lo_um <= w.back())
          throw InputError(name, fmt::format("/tabulated/bands/{}/wavelength_um", i),
                           fmt::format("overlaps the refractive-index table ({}–{} µm): a "
                                       "wavelength has one method",
                                       w.front(), w.back()));
      }
    }
  } else if (kind == "tabulated") {
    m.kind = MaterialKind::tabulated;
    m.tabulated = parse_tabulated(root.object("tabulated"));
  } else if (kind == "thin-flake") {
    m.kind = MaterialKind::thin_flake;
    m.flake = parse_flake(root.object("flake"));
  } else {
    throw root.error("kind", fmt::format("unknown kind '{}' (expected \"mie\", \"tabulated\" or "
                                         "\"thin-flake\")",
                                         kind));
  }
  root.finish();
  return m;
}

}  // namespace obscura
