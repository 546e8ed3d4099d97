"""obscura.validate: the canonical cases with known answers, the rows
`obscura validate --json` prints."""
import json
import math
import subprocess

import pytest

import obscura
from conftest import cli_error


def cli_rows(cli, *args):
    p = subprocess.run([cli, "validate", *map(str, args), "--json"], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    return json.loads(p.stdout)


def test_rows_are_the_clis_for_the_same_seed(cli):
    rows = obscura.validate("emitting-slab", tau=0.1, temperature=400, seed=3, threads=2)
    # The Monte Carlo estimate is the same for any thread count.
    assert rows == cli_rows(cli, "emitting-slab", "--tau", 0.1, "--temperature", 400,
                            "--seed", 3, "--threads", 1)
    (row,) = rows
    assert row["reference"] == pytest.approx(-math.expm1(-0.1), rel=1e-12)  # B(T)(1 − e^−τ)/B(T)
    assert row["pass"] is True
    assert abs(row["obtained"] - row["reference"]) <= max(3 * row["stderr"],
                                                          row["tolerance"] * row["reference"])


def test_other_methods_and_cases(cli):
    rows = obscura.validate("equilibrium", method="emission-absorption", albedo=0, tau=2,
                            samples=20000)
    assert rows == cli_rows(cli, "equilibrium", "--method", "emission-absorption", "--albedo", 0,
                            "--tau", 2, "--samples", 20000)
    assert rows[0]["reference"] > 0 and rows[0]["samples"] > 0


def test_bad_parameters_raise_the_clis_errors(cli):
    with pytest.raises(obscura.InputError) as e:
        obscura.validate("slab", mu0=0.5)
    # The library names the CLI's options, in Python too.
    assert str(e.value) == cli_error(cli, "validate", "slab", "--mu0", 0.5)
    assert e.value.field == "--mu0"
    with pytest.raises(obscura.InputError, match="^case: unknown case 'slabs'"):
        obscura.validate("slabs")
    with pytest.raises(obscura.InputError, match="^--method: unknown render method 'mc'"):
        obscura.validate("furnace", method="mc")
    with pytest.raises(obscura.InputError, match="^--incidence: unknown incidence"):
        obscura.validate("slab", incidence="grazing")
    with pytest.raises(obscura.InputError) as e:
        obscura.validate("furnace", method="emission-absorption")
    assert str(e.value) == cli_error(cli, "validate", "furnace", "--method", "emission-absorption")
