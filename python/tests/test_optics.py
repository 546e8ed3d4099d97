"""Mie efficiencies from Python: what `obscura mie` prints."""
import pytest

import obscura


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
