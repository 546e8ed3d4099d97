#include "obscura/prep/dispersion/dispersion_config.h"

#include <fmt/format.h>

#include <cmath>

namespace obscura {

namespace {

// A burning device at the default 10 puffs/s would need 28 hours of burn to
// reach this; anything larger is a unit mistake, and would exhaust memory.
constexpr long long kMaxPuffsPerDevice = 1000000;

class Checker {
 public:
  explicit Checker(const DispersionConfig& c) : c_(c) {}
  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw InputError(c_.source, c_.json_path + "/" + field, what);
  }
  void finite(const std::string& field, double v) const {
    if (!std::isfinite(v)) fail(field, "expected a finite number");
  }
  // `unit` is "" for dimensionless values, else " g", " m/s", ...
  void positive(const std::string& field, double v, const char* unit) const {
    if (!(std::isfinite(v) && v > 0))
      fail(field, fmt::format("expected a number > 0{}, found {}", unit, v));
  }
  void non_negative(const std::string& field, double v, const char* unit) const {
    if (!(std::isfinite(v) && v >= 0))
      fail(field, fmt::format("expected a number >= 0{}, found {}", unit, v));
  }

 private:
  const DispersionConfig& c_;
};

void validate_device(const Checker& check, const SmokeDevice& d, const DispersionConfig& c,
                     const std::string& base) {
  if (!(std::isfinite(d.x_m) && std::isfinite(d.y_m)))
    check.fail(base + "position_m", "expected finite coordinates");
  check.non_negative(base + "release_height_m", d.release_height_m, " m");
  check.finite(base + "start_s", d.start_s);
  check.non_negative(base + "burn_time_s", d.burn_time_s, " s");
  check.positive(base + "agent_mass_g", d.agent_mass_g, " g");
  check.positive(base + "yield_factor", d.yield_factor, "");
  check.positive(base + "initial_sigma_m", d.initial_sigma_m, " m");
  check.finite(base + "source_temperature_excess_k", d.source_temperature_excess_k);
  if (!(c.ambient_temperature_k + d.source_temperature_excess_k > 0))
    check.fail(base + "source_temperature_excess_k",
               fmt::format("ambient {} K plus excess {} K must stay above 0 K",
                           c.ambient_temperature_k, d.source_temperature_excess_k));
  check.positive(base + "temperature_decay_time_s", d.temperature_decay_time_s, " s");
  check.positive(base + "puffs_per_second", d.puffs_per_second, " per second");
  const double puffs = d.burn_time_s * d.puffs_per_second;
  if (puffs > static_cast<double>(kMaxPuffsPerDevice))
    check.fail(base + "puffs_per_second",
               fmt::format("{} s of burn at {} puffs/s is {:.3g} puffs; at most {} per device",
                           d.burn_time_s, d.puffs_per_second, puffs, kMaxPuffsPerDevice));
}

SmokeDevice parse_device(JsonObject o, int index) {
  SmokeDevice d;
  d.name = o.string_or("name", fmt::format("device {}", index));
  const std::vector<double> xy = o.numbers("position_m");
  if (xy.size() != 2)
    throw o.error("position_m",
                  fmt::format("expected 2 numbers [x east, y north] in m, found {} (the height "
                              "is release_height_m)",
                              xy.size()));
  d.x_m = xy[0];
  d.y_m = xy[1];
  d.release_height_m = o.number_or("release_height_m", d.release_height_m);
  d.start_s = o.number_or("start_s", d.start_s);
  d.burn_time_s = o.number_or("burn_time_s", d.burn_time_s);
  d.agent_mass_g = o.number("agent_mass_g");
  d.yield_factor = o.number_or("yield_factor", d.yield_factor);
  d.initial_sigma_m = o.number_or("initial_sigma_m", d.initial_sigma_m);
  d.source_temperature_excess_k =
      o.number_or("source_temperature_excess_k", d.source_temperature_excess_k);
  d.temperature_decay_time_s = o.number_or("temperature_decay_time_s", d.temperature_decay_time_s);
  d.puffs_per_second = o.number_or("puffs_per_second", d.puffs_per_second);
  o.finish();
  return d;
}

}  // namespace

void validate_dispersion_config(const DispersionConfig& c) {
  const Checker check(c);
  if (c.devices.empty()) check.fail("devices", "expected at least one smoke device");
  check.positive("wind/speed_m_s", c.wind.speed_m_s, " m/s");
  check.finite("wind/from_deg", c.wind.from_deg);
  check.positive("wind/reference_height_m", c.wind.reference_height_m, " m");
  if (!(std::isfinite(c.wind.power_law_exponent) && c.wind.power_law_exponent >= 0 &&
        c.wind.power_law_exponent <= 1))
    check.fail("wind/power_law_exponent",
               fmt::format("expected a number in [0, 1], found {}", c.wind.power_law_exponent));
  check.positive("wind/minimum_height_m", c.wind.minimum_height_m, " m");
  check.positive("ambient_temperature_k", c.ambient_temperature_k, " K");
  for (std::size_t i = 0; i < c.devices.size(); ++i)
    validate_device(check, c.devices[i], c, fmt::format("devices/{}/", i));
}

DispersionConfig parse_dispersion_config(JsonObject o) {
  DispersionConfig c;
  c.source = o.file();
  c.json_path = o.path();

  if (o.has("stability")) {
    const std::string s = o.string("stability");
    const auto parsed = parse_stability_class(s);
    if (!parsed)
      throw o.error("stability", fmt::format("unknown stability class \"{}\" (expected one of "
                                             "A, B, C, D, E, F)",
                                             s));
    c.stability = *parsed;
  }
  if (o.has("sigma_set")) {
    const std::string s = o.string("sigma_set");
    const auto parsed = parse_sigma_set(s);
    if (!parsed)
      throw o.error("sigma_set", fmt::format("unknown sigma set \"{}\" (expected \"ccps-puff\" or "
                                             "\"briggs-open-country\")",
                                             s));
    c.sigma_set = *parsed;
  }
  c.ambient_temperature_k = o.number_or("ambient_temperature_k", c.ambient_temperature_k);

  JsonObject w = o.object("wind");
  c.wind.speed_m_s = w.number("speed_m_s");
  c.wind.from_deg = w.number("from_deg");
  c.wind.reference_height_m = w.number_or("reference_height_m", c.wind.reference_height_m);
  c.wind.power_law_exponent =
      w.number_or("power_law_exponent", default_wind_profile_exponent(c.stability));
  c.wind.minimum_height_m = w.number_or("minimum_height_m", c.wind.minimum_height_m);
  w.finish();

  const nlohmann::json& devices = o.array("devices");
  for (std::size_t i = 0; i < devices.size(); ++i)
    c.devices.push_back(parse_device(
        JsonObject(devices[i], o.file(), fmt::format("{}/{}", o.path_of("devices"), i)),
        static_cast<int>(i)));
  o.finish();

  validate_dispersion_config(c);
  return c;
}

}  // namespace obscura
