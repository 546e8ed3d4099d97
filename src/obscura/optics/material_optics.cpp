// A material's bulk optics at a wavelength and humidity (optics/material.h):
// Mie for tabulated refractive indices (with humidity growth), tabulated
// bands, and the thin-flake rule.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <numbers>

#include "obscura/core/error.h"
#include "obscura/core/parallel.h"
#include "obscura/optics/material.h"

namespace obscura {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The size integral's tolerance. Published coefficients are known to a few
// per cent at best (docs/domain.md §2.2); 1e-3 keeps the quadrature well below
// that and converges for weakly absorbing fog drops whose absorption sits in
// unresolved Mie resonances (water, MMD 10 µm, at 1.064 µm does not reach
// bulk_optics' default 1e-4 within its interval limit).
constexpr double kMaterialTolerance = 1e-3;

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
