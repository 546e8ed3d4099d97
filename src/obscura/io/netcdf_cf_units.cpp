#include "obscura/io/netcdf_cf_units.h"

#include <cctype>

namespace obscura::netcdf_cf {

std::string trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string_view::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n");
  return std::string(s.substr(b, e - b + 1));
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::optional<double> length_to_m(const std::string& units) {
  const std::string u = trim(units);
  for (const char* m : {"m", "metre", "meter", "metres", "meters"})
    if (u == m) return 1.0;
  for (const char* km : {"km", "kilometre", "kilometer", "kilometres", "kilometers"})
    if (u == km) return 1000.0;
  return std::nullopt;
}

std::optional<double> time_to_s(const std::string& units) {
  std::string u = trim(units);
  const std::string l = lower(u);
  const auto since = l.find(" since ");
  const std::string unit = trim(since == std::string::npos ? l : l.substr(0, since));
  for (const char* s : {"s", "sec", "secs", "second", "seconds"})
    if (unit == s) return 1.0;
  for (const char* s : {"min", "mins", "minute", "minutes"})
    if (unit == s) return 60.0;
  for (const char* s : {"h", "hr", "hrs", "hour", "hours"})
    if (unit == s) return 3600.0;
  for (const char* s : {"d", "day", "days"})
    if (unit == s) return 86400.0;
  return std::nullopt;
}

// Mass per volume: "<mass> m-3", "<mass> m^-3", "<mass>/m3", "<mass>/m^3",
// with mass kg, g, mg, ug (or µg); spaces and '.' separators are ignored.
std::optional<double> concentration_to_g_m3(const std::string& units) {
  std::string u;
  for (char c : trim(units))
    if (c != ' ' && c != '.') u += c;
  for (const char* volume : {"m-3", "m^-3", "m**-3", "/m3", "/m^3", "/m**3"}) {
    const std::string v = volume;
    if (u.size() <= v.size() || u.compare(u.size() - v.size(), v.size(), v) != 0) continue;
    const std::string mass = u.substr(0, u.size() - v.size());
    if (mass == "kg") return 1000.0;
    if (mass == "g") return 1.0;
    if (mass == "mg") return 1e-3;
    if (mass == "ug" || mass == "\xC2\xB5g" || mass == "\xCE\xBCg") return 1e-6;
  }
  return std::nullopt;
}

std::optional<double> temperature_offset_to_k(const std::string& units) {
  const std::string u = trim(units);
  for (const char* k : {"K", "kelvin", "Kelvin", "degK", "degrees_K"})
    if (u == k) return 0.0;
  for (const char* c : {"degC", "deg_C", "celsius", "Celsius", "degree_Celsius", "degrees_Celsius",
                        "degree_C", "degrees_C"})
    if (u == c) return 273.15;
  return std::nullopt;
}

}  // namespace obscura::netcdf_cf
