"""The optics layer from Python: Mie efficiencies, what `obscura mie`
prints, and a material's bulk coefficients, what `obscura optics` prints."""
import json
import subprocess

import numpy as np
import pytest

import obscura
from conftest import cli_error


def test_mie_of_a_water_sphere_matches_the_cli_tour():
    e = obscura.mie(10.0, complex(1.33, 0.0))
    assert e["qext"] == pytest.approx(2.20654871, abs=5e-9)
    assert e["qsca"] == pytest.approx(2.20654871, abs=5e-9)
    assert e["qabs"] == 0.0
    assert e["g"] == pytest.approx(0.7124592697, abs=5e-11)
    assert e["terms"] == 26


def test_mie_refuses_a_negative_absorption_index():
    with pytest.raises(obscura.InputError) as e:
        obscura.mie(1.0, complex(1.5, -0.1))
    assert e.value.field == "refractive_index.imag"


def _cli_json(cli, *args):
    p = subprocess.run([cli, *map(str, args)], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    return json.loads(p.stdout)


@pytest.mark.parametrize("material,wavelengths,humidity", [
    ("soot", [0.55, 4, 10], 0.0),
    ("phosphorus_smoke", [0.55, 1.064, 10], 0.6),  # Mie with growth, then a tabulated band
])
def test_material_optics_are_the_clis(cli, material, wavelengths, humidity):
    o = obscura.optics(material, wavelengths, relative_humidity=humidity)
    ref = _cli_json(cli, "optics", "--material", material, "--wavelengths",
                    ",".join(map(str, wavelengths)), "--humidity", humidity, "--json")
    assert o["material"] == ref["material"] and o["mass_basis"] == ref["mass_basis"]
    assert o["units"]["mass_extinction_m2_g"] == "m2 g-1"
    for key in ["wavelength_um", "mass_extinction_m2_g", "mass_scattering_m2_g",
                "mass_absorption_m2_g", "single_scattering_albedo", "asymmetry",
                "hydrated_mass_factor"]:
        assert o[key].dtype == np.float64 and o[key].shape == (len(wavelengths),)
        # The CLI prints every double exactly; null where the sources give none.
        expected = [np.nan if r[key] is None else r[key] for r in ref["rows"]]
        np.testing.assert_array_equal(o[key], expected, err_msg=key)
    assert o["method"] == [r["method"] for r in ref["rows"]]
    lo, hi = zip(*(r["mass_extinction_range_m2_g"] for r in ref["rows"]))
    np.testing.assert_array_equal(o["mass_extinction_min_m2_g"], lo)
    np.testing.assert_array_equal(o["mass_extinction_max_m2_g"], hi)


def test_extinction_is_absorption_plus_scattering():
    o = obscura.optics("soot", np.linspace(0.4, 12, 7))
    np.testing.assert_allclose(o["mass_extinction_m2_g"],
                               o["mass_absorption_m2_g"] + o["mass_scattering_m2_g"], rtol=1e-12)
    np.testing.assert_allclose(o["single_scattering_albedo"],
                               o["mass_scattering_m2_g"] / o["mass_extinction_m2_g"], rtol=1e-12)


def test_bad_material_arguments_raise_input_errors(cli):
    with pytest.raises(obscura.InputError) as e:
        obscura.optics("no_such_smoke", [0.55])
    assert e.value.field == "material"
    assert e.value.detail == cli_error(cli, "optics", "--material", "no_such_smoke",
                                       "--wavelengths", "0.55").split(": ", 1)[1]
    with pytest.raises(obscura.InputError, match="relative_humidity"):
        obscura.optics("soot", [0.55], relative_humidity=1.5)
    with pytest.raises(obscura.InputError, match="wavelengths_um: wavelengths must be > 0"):
        obscura.optics("soot", [0.55, -1])
    with pytest.raises(obscura.InputError, match="wavelength_um"):
        obscura.optics("soot", [40.0])  # beyond the index table
