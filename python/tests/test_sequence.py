"""obscura.render_sequence: per sensor an xarray.Dataset (time, band, y, x)
with CF-1.10 attributes, the target mask and screening metrics over time;
the same content as a dict of numpy arrays without xarray."""
import json
import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest
import xarray

import obscura
from conftest import SMALL_SCENE


def test_a_sequence_is_a_cf_dataset_equal_to_renders_at_each_time(scene_dict):
    scene = obscura.Scene.from_dict(scene_dict)
    times = [0.0, 0.5, 1.0]
    seen = []
    out = obscura.render_sequence(scene, times, method="path-tracer", seed=5, progress=seen.append)
    assert list(out) == ["ir"]
    ds = out["ir"]
    assert isinstance(ds, xarray.Dataset)
    assert dict(ds.radiance.sizes) == {"time": 3, "band": 2, "y": 16, "x": 24}
    assert list(ds.band.values) == ["mwir", "lwir"]
    np.testing.assert_array_equal(ds.time.values, times)
    assert ds.time.attrs["units"] == "s"
    assert ds.radiance.attrs["units"] == "W m-2 sr-1"
    assert ds.radiance_stderr.attrs["units"] == "W m-2 sr-1"
    assert ds.transmittance.attrs["units"] == "1"
    assert ds.apparent_temperature.attrs["standard_name"] == "brightness_temperature"
    assert ds.attrs["Conventions"] == "CF-1.10"
    assert ds.attrs["method"] == "path-tracer" and ds.attrs["seed"] == 5
    prov = json.loads(ds.attrs["provenance"])
    assert prov["software"] == "obscura" and prov["seed"] == 5
    assert {p["frame"] for p in seen} == {0, 1, 2}
    # Each frame is what render() gives at that time with the same settings.
    for i, t in enumerate(times):
        img = obscura.render(scene, time=t, method="path-tracer", seed=5)["ir"]
        for b, name in enumerate(["mwir", "lwir"]):
            np.testing.assert_array_equal(ds.radiance.values[i, b], img.bands[name].radiance)
            np.testing.assert_array_equal(ds.radiance_stderr.values[i, b],
                                          img.bands[name].radiance_stderr)


def test_the_target_mask_and_screening_metrics_come_over_time(scene_dict):
    ds = obscura.render_sequence(obscura.Scene.from_dict(scene_dict), [0.0, 2.0])["ir"]
    assert "radiance_stderr" not in ds  # emission-absorption has no standard error
    mask = ds.target_mask.values
    assert mask.shape == (16, 24) and (mask == 1).sum() == ds.target_pixels.values[0, 0] > 0
    assert dict(ds.transmittance_mean.sizes) == {"time": 2, "band": 2}
    # The mean over the target pixels is the metric's target transmittance.
    tr = ds.transmittance.values[0, 1][mask == 1].astype(np.float64).mean()
    assert ds.transmittance_mean.values[0, 1] == pytest.approx(tr, rel=1e-6)
    assert ds.delta_t.attrs["units"] == "K"
    assert json.loads(ds.attrs["screening"])[0]["sensor"] == "ir"


def test_times_must_increase():
    scene = obscura.Scene.from_dict(SMALL_SCENE)
    with pytest.raises(obscura.InputError, match=r"^times: must be strictly increasing"):
        obscura.render_sequence(scene, [1.0, 0.0])
    with pytest.raises(obscura.InputError, match=r"^times: must hold at least one time"):
        obscura.render_sequence(scene, [])


def test_a_band_outside_the_clouds_samples_is_a_runtime_warning_given_once(scene_dict):
    # The cloud is sampled at 4 and 10 µm only, as the CLI warns on stderr.
    scene_dict["sensors"][0]["bands"] = ["visible", "lwir"]
    scene = obscura.Scene.from_dict(scene_dict)
    with pytest.warns(RuntimeWarning) as caught:
        obscura.render_sequence(scene, [0.0, 1.0, 2.0])
    messages = [str(w.message) for w in caught]
    assert messages == ["sensor ir, band visible (0.4-0.7 µm) lies outside the clouds' spectral "
                        "samples (4-10 µm): their coefficients are held at the 4 µm values "
                        "across it; prepare the clouds at wavelengths in the band"]


FALLBACK = textwrap.dedent("""
    import json, sys
    sys.modules["xarray"] = None  # import xarray now raises ImportError
    import obscura
    out = obscura.render_sequence(obscura.Scene.from_dict(json.loads(sys.argv[1])), [0.0, 1.0])
    d = out["ir"]
    r = d["data_vars"]["radiance"]
    print(type(d).__name__, r["dims"], r["data"].shape, r["attrs"]["units"], d["attrs"]["Conventions"])
""")


def test_without_xarray_the_same_content_comes_as_a_dict():
    p = subprocess.run([sys.executable, "-c", FALLBACK, json.dumps(SMALL_SCENE)],
                       capture_output=True, text=True, timeout=120, env=os.environ.copy())
    assert p.returncode == 0, p.stderr
    assert p.stdout.strip() == "dict ('time', 'band', 'y', 'x') (2, 2, 16, 24) W m-2 sr-1 CF-1.10"
