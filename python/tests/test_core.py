"""Planck, band radiance, apparent temperature and bands from Python: the
numbers `obscura radiance` prints, and its error messages."""
import numpy as np
import pytest

import obscura
from conftest import cli_error


def test_band_radiance_is_what_the_cli_prints():
    # README tour: `obscura radiance --temperature 300 --band lwir` → 38.5004.
    assert float(obscura.band_radiance(300.0, "lwir")) == pytest.approx(38.5004, abs=5e-5)


def test_apparent_temperature_inverts_band_radiance_over_arrays():
    t = np.array([[200.0, 300.0], [800.0, 2500.0]])
    for band in ("mwir", obscura.Band("8:12"), obscura.Band.flat("b", 3.0, 5.0)):
        back = obscura.apparent_temperature(obscura.band_radiance(t, band), band)
        assert back.shape == t.shape
        np.testing.assert_allclose(back, t, rtol=0, atol=1e-3)


def test_planck_matches_the_formula_and_broadcasts():
    h, c, k = 6.62607015e-34, 299792458.0, 1.380649e-23
    wl = np.array([1.0, 4.0, 10.0])
    expected = 2 * h * c**2 / (wl * 1e-6) ** 5 / np.expm1(h * c / (wl * 1e-6 * k * 300.0)) * 1e-6
    np.testing.assert_allclose(obscura.planck(wl, 300.0), expected, rtol=1e-12)
    assert obscura.planck(wl[:, None], np.array([300.0, 600.0])).shape == (3, 2)


def test_band_properties():
    b = obscura.Band("mwir")
    assert (b.name, b.lo_um, b.hi_um) == ("mwir", 3.0, 5.0)
    assert "lwir" in obscura.Band.preset_names()


def test_a_bad_band_raises_the_cli_message(cli):
    with pytest.raises(obscura.InputError) as e:
        obscura.band_radiance(300.0, "nope")
    expected = cli_error(cli, "radiance", "--temperature", "300", "--band", "nope")
    # The CLI names its option --band; Python names the argument band.
    assert str(e.value) == expected.replace("--band", "band", 1)
    assert isinstance(e.value, obscura.Error) and isinstance(e.value, ValueError)
    assert e.value.field == "band"
