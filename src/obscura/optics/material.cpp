#include "obscura/optics/material.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <functional>
#include <limits>
#include <numbers>

#include "obscura/core/data_directory.h"
#include "obscura/core/error.h"
#include "obscura/core/parallel.h"
#include "obscura/io/json_reader.h"

namespace obscura {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The size integral's tolerance. Published coefficients are known to a few
// per cent at best (docs/domain.md §2.2); 1e-3 keeps the quadrature well below
// that and converges for weakly absorbing fog drops whose absorption sits in
// unresolved Mie resonances (water, MMD 10 µm, at 1.064 µm does not reach
// bulk_optics' default 1e-4 within its interval limit).
constexpr double kMaterialTolerance = 1e-3;

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

bool covers(const RefractiveIndexTable& t, double lambda) {
  return lambda >= t.wavelength_um.front() && lambda <= t.wavelength_um.back();
}

// Linear interpolation of n and k; `lambda` within the table.
std::complex<double> index_at(const RefractiveIndexTable& t, double lambda) {
  const auto& w = t.wavelength_um;
  auto hi = std::upper_bound(w.begin(), w.end(), lambda);
  if (hi == w.end()) return {t.n.back(), t.k.back()};  // lambda == last row
  if (hi == w.begin()) return {t.n.front(), t.k.front()};
  const std::size_t j = static_cast<std::size_t>(hi - w.begin()), i = j - 1;
  const double s = (lambda - w[i]) / (w[j] - w[i]);
  return {t.n[i] + s * (t.n[j] - t.n[i]), t.k[i] + s * (t.k[j] - t.k[i])};
}

std::string coverage(const Material& m) {
  std::vector<std::string> parts;
  if (m.mie)
    parts.push_back(fmt::format("Mie {}–{} µm", m.mie->index.wavelength_um.front(),
                                m.mie->index.wavelength_um.back()));
  if (m.tabulated) {
    std::string bands;
    for (const auto& b : m.tabulated->bands)
      bands += (bands.empty() ? "" : ", ") + (b.lo_um == b.hi_um
                                                  ? fmt::format("{}", b.lo_um)
                                                  : fmt::format("{}–{}", b.lo_um, b.hi_um));
    parts.push_back("tabulated " + bands + " µm");
  }
  std::string out;
  for (const auto& p : parts) out += (out.empty() ? "" : "; ") + p;
  return out;
}

[[noreturn]] void no_data(const Material& m, double lambda) {
  throw InputError(m.file, "wavelength_um",
                   fmt::format("material '{}' has no data at {} µm (it covers: {})", m.name, lambda,
                               coverage(m)));
}

void set_unknown_scattering(MaterialOptics& out) {
  out.mass_scattering_m2_g = out.mass_absorption_m2_g = kNaN;
  out.single_scattering_albedo = out.asymmetry = kNaN;
}

// Band values inside a band; linear interpolation between the facing edges
// of two neighbouring bands; no extrapolation.
bool tabulated_at(const TabulatedOptics& t, double lambda, MaterialOptics& out) {
  const auto& bands = t.bands;
  auto fill = [&](const TabulatedBand& a, const TabulatedBand& b, double s) {
    auto mix = [s](double x, double y) { return x + s * (y - x); };
    out.mass_extinction_m2_g = mix(a.mass_extinction_m2_g.value, b.mass_extinction_m2_g.value);
    out.mass_extinction_min_m2_g = mix(a.mass_extinction_m2_g.min, b.mass_extinction_m2_g.min);
    out.mass_extinction_max_m2_g = mix(a.mass_extinction_m2_g.max, b.mass_extinction_m2_g.max);
    if (a.albedo && b.albedo) {
      out.single_scattering_albedo = mix(a.albedo->value, b.albedo->value);
      out.mass_scattering_m2_g = out.single_scattering_albedo * out.mass_extinction_m2_g;
      out.mass_absorption_m2_g = out.mass_extinction_m2_g - out.mass_scattering_m2_g;
    } else {
      set_unknown_scattering(out);
    }
    out.asymmetry = a.asymmetry && b.asymmetry ? mix(a.asymmetry->value, b.asymmetry->value) : kNaN;
  };
  for (std::size_t i = 0; i < bands.size(); ++i) {
    const auto& b = bands[i];
    if (lambda >= b.lo_um && lambda <= b.hi_um) {
      fill(b, b, 0.0);
      out.method = "tabulated";
      out.note = b.note;
      return true;
    }
    if (i + 1 < bands.size() && lambda > b.hi_um && lambda < bands[i + 1].lo_um) {
      const auto& c = bands[i + 1];
      fill(b, c, (lambda - b.hi_um) / (c.lo_um - b.hi_um));
      out.method = "tabulated (interpolated between bands)";
      out.note = fmt::format("between the bands {}–{} µm and {}–{} µm", b.lo_um, b.hi_um, c.lo_um,
                             c.hi_um);
      return true;
    }
  }
  return false;
}

void check_humidity(const std::string& file, double rh) {
  if (!(rh >= 0 && rh < 1))
    throw InputError(file, "relative_humidity",
                     fmt::format("must lie in [0, 1) (a fraction, not per cent), found {}", rh));
}

MaterialOptics mie_at(const Material& material, double lambda, double rh, int threads) {
  const MieModel& mie = *material.mie;
  const HumidityState h = humidity_state(mie, rh);
  std::complex<double> m = index_at(mie.index, lambda);
  if (mie.humidity && h.water_volume_fraction > 0) {
    const std::complex<double> water = index_at(mie.humidity->water_index, lambda);
    m = (1 - h.water_volume_fraction) * m + h.water_volume_fraction * water;
  }
  LognormalDistribution d = mie.distribution;
  d.median_radius_um *= h.radius_growth;
  BulkOpticsOptions options;
  options.relative_tolerance = kMaterialTolerance;
  options.threads = threads;
  BulkOptics b;
  try {
    b = bulk_optics(d, lambda, m, h.density_g_cm3, options);
  } catch (const InputError& e) {
    throw InputError(material.file, e.field(), e.detail());
  }
  MaterialOptics out;
  out.mass_extinction_m2_g = b.mass_extinction_m2_g * h.mass_factor;
  out.mass_scattering_m2_g = b.mass_scattering_m2_g * h.mass_factor;
  out.mass_absorption_m2_g = b.mass_absorption_m2_g * h.mass_factor;
  // Q_ext and Q_sca are separate sums: for k = 0 their ratio may exceed 1 by
  // a rounding error.
  out.single_scattering_albedo = std::min(1.0, b.single_scattering_albedo);
  out.asymmetry = b.asymmetry;
  out.mass_extinction_min_m2_g = out.mass_extinction_max_m2_g = out.mass_extinction_m2_g;
  out.hydrated_mass_factor = h.mass_factor;
  out.method = "mie";
  return out;
}

MaterialOptics flake_at(const Material& material, double lambda) {
  const ThinFlakeModel& f = *material.flake;
  MaterialOptics out;
  out.method = "thin-flake";
  out.mass_extinction_m2_g = 1.0 / (f.density_g_cm3 * f.thickness_um.value);
  out.mass_extinction_min_m2_g = 1.0 / (f.density_g_cm3 * f.thickness_um.max);
  out.mass_extinction_max_m2_g = 1.0 / (f.density_g_cm3 * f.thickness_um.min);
  std::vector<std::string> notes;
  if (f.diameter_um && f.diameter_um->value <= lambda)
    notes.push_back(fmt::format(
        "flakes {} µm across are not wider than the wavelength: the rule overestimates α here "
        "(docs/domain.md §2.4)",
        f.diameter_um->value));
  if (f.index && covers(*f.index, lambda)) {
    const std::complex<double> m = index_at(*f.index, lambda);
    const RandomFacetReflection r = random_facet_reflection(m);
    // Large-particle limit: Q_ext = 2, half diffracted into the forward peak
    // (g = 1), half intercepted by the geometric cross-section, of which the
    // reflectance R is scattered and 1 − R absorbed (opaque flake).
    out.single_scattering_albedo = 0.5 * (1.0 + r.reflectance);
    out.asymmetry = (1.0 + r.reflectance * r.asymmetry) / (1.0 + r.reflectance);
    out.mass_scattering_m2_g = out.single_scattering_albedo * out.mass_extinction_m2_g;
    out.mass_absorption_m2_g = out.mass_extinction_m2_g - out.mass_scattering_m2_g;
    const double depth_um = m.imag() > 0 ? lambda / (4 * std::numbers::pi * m.imag())
                                         : std::numeric_limits<double>::infinity();
    if (f.thickness_um.value < depth_um)
      notes.push_back(fmt::format(
          "flakes {} µm thick are thinner than the absorption depth λ/(4πk) = {:.3g} µm: not "
          "opaque, so the rule and the opaque-flake ω, g are approximate",
          f.thickness_um.value, depth_um));
  } else {
    set_unknown_scattering(out);
    if (f.index)
      notes.push_back(fmt::format("no refractive index at {} µm: albedo and g unknown", lambda));
  }
  for (const auto& n : notes) out.note += (out.note.empty() ? "" : "; ") + n;
  return out;
}

MaterialOptics optics_impl(const Material& material, double lambda, double rh, int threads) {
  if (!std::isfinite(lambda) || !(lambda > 0))
    throw InputError(material.file, "wavelength_um",
                     fmt::format("must be a wavelength > 0 µm, found {}", lambda));
  check_humidity(material.file, rh);
  MaterialOptics out;
  if (material.kind == MaterialKind::thin_flake) {
    out = flake_at(material, lambda);
  } else if (material.mie && covers(material.mie->index, lambda)) {
    out = mie_at(material, lambda, rh, threads);
  } else if (!material.tabulated || !tabulated_at(*material.tabulated, lambda, out)) {
    no_data(material, lambda);
  } else if (rh > 0 && material.mie && material.mie->humidity) {
    out.note +=
        std::string(out.note.empty() ? "" : "; ") + "tabulated values do not depend on humidity";
  }
  out.wavelength_um = lambda;
  out.relative_humidity = rh;
  return out;
}

}  // namespace

std::complex<double> refractive_index_at(const RefractiveIndexTable& table, double wavelength_um) {
  if (table.wavelength_um.empty() || !covers(table, wavelength_um))
    throw InputError(
        "", "wavelength_um",
        fmt::format("{} µm is outside the refractive-index table ({}–{} µm)", wavelength_um,
                    table.wavelength_um.empty() ? 0.0 : table.wavelength_um.front(),
                    table.wavelength_um.empty() ? 0.0 : table.wavelength_um.back()));
  return index_at(table, wavelength_um);
}

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

HumidityState humidity_state(const MieModel& mie, double rh) {
  check_humidity("", rh);
  HumidityState s;
  s.relative_humidity = rh;
  s.density_g_cm3 = mie.density_g_cm3;
  if (!mie.humidity) {
    s.solute_mass_fraction = 1;
    return s;
  }
  const HumidityGrowth& h = *mie.humidity;
  // Raoult: water mass per solute mass at water activity RH.
  const double water_per_solute =
      h.water_molar_mass_g_mol / h.solute_molar_mass_g_mol * h.van_t_hoff_factor * rh / (1 - rh);
  const double w = 1.0 / (1.0 + water_per_solute);
  s.solute_mass_fraction = h.reference_solute_mass_fraction;
  if (w >= h.reference_solute_mass_fraction) return s;  // at or drier than the reference
  s.solute_mass_fraction = w;
  const double water_mass = h.reference_solute_mass_fraction / w - 1.0;  // per reference gram
  const double v_ref = 1.0 / mie.density_g_cm3, v_water = water_mass / h.water_density_g_cm3;
  s.mass_factor = 1.0 + water_mass;
  s.radius_growth = std::cbrt((v_ref + v_water) / v_ref);
  s.water_volume_fraction = v_water / (v_ref + v_water);
  s.density_g_cm3 = s.mass_factor / (v_ref + v_water);
  return s;
}

MaterialOptics optics_at(const Material& material, double wavelength_um, double rh) {
  return optics_impl(material, wavelength_um, rh, 0);
}

std::vector<MaterialOptics> optics_at(const Material& material,
                                      std::span<const double> wavelengths_um, double rh,
                                      int threads) {
  std::vector<MaterialOptics> out(wavelengths_um.size());
  if (wavelengths_um.size() == 1) {
    out[0] = optics_impl(material, wavelengths_um[0], rh, threads);
    return out;
  }
  // One wavelength per task, each size integral on one thread; the first
  // failing wavelength (in order) is reported, whatever the scheduling.
  std::vector<std::exception_ptr> errors(wavelengths_um.size());
  parallel_for(wavelengths_um.size(), threads, [&](std::size_t i) {
    try {
      out[i] = optics_impl(material, wavelengths_um[i], rh, 1);
    } catch (...) {
      errors[i] = std::current_exception();
    }
  });
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
  return out;
}

RandomFacetReflection random_facet_reflection(std::complex<double> m) {
  // Midpoint rule in μ = cos θ over [0, 1]; the weight 2 cosθ sinθ dθ is 2μ dμ.
  // m cos θ_t = sqrt(m² − sin²θ) on the principal branch (Im ≥ 0: the
  // transmitted wave decays for k ≥ 0). Unpolarised: R = (|r_s|² + |r_p|²)/2.
  constexpr int kSteps = 4096;
  const std::complex<double> m2 = m * m;
  double reflected = 0, moment = 0;
  for (int i = 0; i < kSteps; ++i) {
    const double mu = (i + 0.5) / kSteps;
    const std::complex<double> mct = std::sqrt(m2 - (1.0 - mu * mu));
    const double rs = std::norm((mu - mct) / (mu + mct));
    const double rp = std::norm((m2 * mu - mct) / (m2 * mu + mct));
    const double r = 0.5 * (rs + rp) * 2.0 * mu / kSteps;
    reflected += r;
    moment += r * (1.0 - 2.0 * mu * mu);  // cos(π − 2θ) = 1 − 2 cos²θ
  }
  return {reflected, reflected > 0 ? moment / reflected : 0.0};
}

}  // namespace obscura
