#pragma once
// The units the CF reader (io/netcdf_cf.h) accepts, as UDUNITS strings
// (CF §3.1). Only the spellings in netcdf_cf_units.cpp are accepted; anything
// else is an error that names the attribute, never a guess. Internal to io/.
#include <optional>
#include <string>
#include <string_view>

namespace obscura::netcdf_cf {

// `s` without leading and trailing white space; lower case.
std::string trim(std::string_view s);
std::string lower(std::string_view s);

// Factor to metres: m or km.
std::optional<double> length_to_m(const std::string& units);
// Factor to seconds: "UNIT" or "UNIT since REFERENCE" (CF §4.4), UNIT s, min,
// h or d. The reference time is not used: frame times are the coordinate
// values converted to seconds.
std::optional<double> time_to_s(const std::string& units);
// Factor to g/m³ of a mass concentration.
std::optional<double> concentration_to_g_m3(const std::string& units);
// Offset to add to get kelvin: K or degC.
std::optional<double> temperature_offset_to_k(const std::string& units);

}  // namespace obscura::netcdf_cf
