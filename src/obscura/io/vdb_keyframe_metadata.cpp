#include "obscura/io/vdb_keyframe_metadata.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <system_error>

#include "obscura/io/vdb_keyframe.h"
#include "obscura/io/vdb_keyframe_layout.h"
#include "obscura/io/vdb_keyframe_placement.h"

namespace obscura::vdb_format {

std::string format_wavelengths(const std::vector<double>& w) {
  std::string out;
  for (std::size_t k = 0; k < w.size(); ++k) {
    if (k > 0) out += ',';
    out += fmt::format("{:.17g}", w[k]);  // 17 significant digits round-trip any double
  }
  return out;
}

std::vector<double> parse_wavelengths(const std::string& text, const std::string& file) {
  std::vector<double> out;
  std::size_t pos = 0;
  while (true) {
    const std::size_t comma = std::min(text.find(',', pos), text.size());
    std::size_t b = pos, e = comma;
    while (b < e && text[b] == ' ') ++b;
    while (e > b && text[e - 1] == ' ') --e;
    double v = 0.0;
    const auto [end, ec] = std::from_chars(text.data() + b, text.data() + e, v);
    if (b == e || ec != std::errc() || end != text.data() + e)
      throw InputError(file, "wavelengths_um",
                       fmt::format("'{}' is not a comma-separated list of numbers (entry {} is "
                                   "'{}')",
                                   text, out.size(), text.substr(b, e - b)));
    out.push_back(v);
    if (comma == text.size()) break;
    pos = comma + 1;
  }
  return out;
}

std::string MetaReader::get_string(const std::string& key) const {
  const auto m = require(key);
  if (auto s = dynamic_cast<const openvdb::StringMetadata*>(m.get())) return s->value();
  throw wrong_type(key, m, "string");
}

long long MetaReader::get_int(const std::string& key) const {
  const auto m = require(key);
  if (auto i = dynamic_cast<const openvdb::Int32Metadata*>(m.get())) return i->value();
  if (auto i = dynamic_cast<const openvdb::Int64Metadata*>(m.get())) return i->value();
  throw wrong_type(key, m, "int");
}

double MetaReader::get_double(const std::string& key) const {
  const auto m = require(key);
  if (auto d = dynamic_cast<const openvdb::DoubleMetadata*>(m.get())) return d->value();
  if (auto f = dynamic_cast<const openvdb::FloatMetadata*>(m.get())) return f->value();
  throw wrong_type(key, m, "double");
}

openvdb::Vec3i MetaReader::get_vec3i(const std::string& key) const {
  const auto m = require(key);
  if (auto v = dynamic_cast<const openvdb::Vec3IMetadata*>(m.get())) return v->value();
  throw wrong_type(key, m, "vec3i");
}

openvdb::Metadata::ConstPtr MetaReader::require(const std::string& key) const {
  auto m = meta_[key];
  if (!m) throw InputError(file_, key, "required file metadata is missing");
  return m;
}

InputError MetaReader::wrong_type(const std::string& key, const openvdb::Metadata::ConstPtr& m,
                                  const char* expected) const {
  return InputError(file_, key,
                    fmt::format("file metadata has type {}, expected {}", m->typeName(), expected));
}

CommonHeader read_common_header(const MetaReader& meta, const openvdb::MetaMap& map,
                                const std::string& file) {
  CommonHeader h;
  const std::string format = meta.get_string("obscura_format");
  if (format != kFormatName)
    throw InputError(file, "obscura_format",
                     fmt::format("is '{}', expected '{}'", format, kFormatName));
  const long long version = meta.get_int("obscura_format_version");
  if (version > kCloudKeyframeFormatVersion)
    throw InputError(file, "obscura_format_version",
                     fmt::format("version {} is newer than this obscura reads ({})", version,
                                 kCloudKeyframeFormatVersion));
  if (version < 1)
    throw InputError(file, "obscura_format_version", fmt::format("invalid version {}", version));
  // Files without obscura_form (other tools, older obscura) are spectral.
  h.form = map[std::string("obscura_form")] ? meta.get_string("obscura_form") : kFormSpectral;
  if (h.form != kFormSpectral && h.form != kFormSpecies)
    throw InputError(
        file, "obscura_form",
        fmt::format("is '{}', expected '{}' or '{}'", h.form, kFormSpectral, kFormSpecies));
  if (meta.get_string("temperature_units") != kTemperatureUnits)
    throw InputError(file, "temperature_units",
                     fmt::format("is '{}', expected '{}'", meta.get_string("temperature_units"),
                                 kTemperatureUnits));

  h.time_s = meta.get_double("time_s");
  if (!(std::isfinite(h.time_s) && h.time_s >= 0.0))
    throw InputError(
        file, "time_s",
        fmt::format("time {} s must be finite and >= 0 (seconds after activation)", h.time_s));

  const long long spectral_count = meta.get_int("spectral_count");
  if (spectral_count <= 0 || spectral_count > 999)  // grid names carry 3 digits
    throw InputError(file, "spectral_count",
                     fmt::format("{} must be between 1 and 999", spectral_count));
  h.wavelengths_um = parse_wavelengths(meta.get_string("wavelengths_um"), file);
  if (static_cast<long long>(h.wavelengths_um.size()) != spectral_count)
    throw InputError(file, "wavelengths_um",
                     fmt::format("lists {} wavelengths but spectral_count is {}",
                                 h.wavelengths_um.size(), spectral_count));

  const openvdb::Vec3i d = meta.get_vec3i("dims");
  h.dims = GridDims{d.x(), d.y(), d.z()};
  return h;
}

void require_units(const MetaReader& meta, const std::string& key, const char* want,
                   const std::string& file) {
  const std::string units = meta.get_string(key);
  if (units != want)
    throw InputError(file, key, fmt::format("is '{}', expected '{}'", units, want));
}

void check_time_and_metadata(const std::string& file, double time_s,
                             const std::map<std::string, std::string>& extra_metadata) {
  if (!(std::isfinite(time_s) && time_s >= 0.0))
    throw InputError(
        file, "time_s",
        fmt::format("time {} s must be finite and >= 0 (seconds after activation)", time_s));
  for (const auto& [key, value] : extra_metadata) {
    if (key.empty()) throw InputError(file, "metadata", "metadata names must not be empty");
    if (reserved_keys().count(key))
      throw InputError(file, key, "is a reserved cloud-keyframe metadata name");
  }
}

openvdb::MetaMap common_metadata(const char* form, double time_s,
                                 const std::vector<double>& wavelengths_um, const GridDims& d,
                                 const GridPlacement& placement,
                                 const std::map<std::string, std::string>& extra_metadata) {
  openvdb::MetaMap meta;
  meta.insertMeta("obscura_format", openvdb::StringMetadata(kFormatName));
  meta.insertMeta("obscura_format_version", openvdb::Int32Metadata(kCloudKeyframeFormatVersion));
  meta.insertMeta("obscura_form", openvdb::StringMetadata(form));
  meta.insertMeta("time_s", openvdb::DoubleMetadata(time_s));
  meta.insertMeta("wavelengths_um", openvdb::StringMetadata(format_wavelengths(wavelengths_um)));
  meta.insertMeta("spectral_count",
                  openvdb::Int32Metadata(static_cast<int>(wavelengths_um.size())));
  meta.insertMeta("dims", openvdb::Vec3IMetadata(openvdb::Vec3i(d.nx, d.ny, d.nz)));
  meta.insertMeta("temperature_units", openvdb::StringMetadata(kTemperatureUnits));
  meta.insertMeta("placement", openvdb::StringMetadata(format_placement(placement)));
  for (const auto& [key, value] : extra_metadata)
    meta.insertMeta(key, openvdb::StringMetadata(value));
  return meta;
}

}  // namespace obscura::vdb_format
