"""obscura.render: numpy images with units, bit-identical to the CLI's EXR
for the same scene and seed, deterministic for any thread count."""
import subprocess

import numpy as np
import pytest

import obscura
from conftest import write_scene


def test_images_are_float32_arrays_of_the_sensor_size_with_units(scene_dict):
    images = obscura.render(obscura.Scene.from_dict(scene_dict))
    assert list(images) == ["ir"]
    ir = images["ir"]
    assert (ir.width, ir.height) == (24, 16)
    assert list(ir.bands) == ["mwir", "lwir"]
    lwir = ir.bands["lwir"]
    for name in ("radiance", "transmittance", "apparent_temperature"):
        a = getattr(lwir, name)
        assert a.dtype == np.float32 and a.shape == (16, 24)
        assert not a.flags.writeable
    assert lwir.radiance_stderr is None  # emission-absorption is not Monte Carlo
    assert obscura.BandImage.units["radiance"] == "W m-2 sr-1"
    assert obscura.BandImage.units["apparent_temperature"] == "K"
    # The cloud sits in front of part of the view only.
    assert lwir.transmittance.min() < 0.9 and lwir.transmittance.max() == 1.0
    # Apparent temperature is the inverse of the band radiance.
    np.testing.assert_allclose(
        obscura.band_radiance(lwir.apparent_temperature.astype(np.float64), "lwir"),
        lwir.radiance, rtol=1e-5)


@pytest.mark.parametrize("method", ["emission-absorption", "path-tracer"])
def test_a_render_equals_the_cli_exr_bit_for_bit(tmp_path, cli, scene_dict, method):
    scene_dict["render"].update({"method": method, "seed": 7, "samples_per_pixel": 2})
    path = write_scene(tmp_path, scene_dict)
    out = tmp_path / "out"
    subprocess.run([cli, "render", str(path), "-o", str(out), "--at", "1.5"], check=True,
                   capture_output=True)
    exr = obscura.read_exr(out / "ir.exr")
    mine = obscura.render(obscura.Scene.load(path), time=1.5)["ir"]
    assert exr["attributes"]["obscura.sensor"] == "ir"
    compared = 0
    for name, band in mine.bands.items():
        for q in ("radiance", "transmittance", "apparent_temperature", "radiance_stderr"):
            a = getattr(band, q)
            if a is None:
                assert f"{name}.{q}" not in exr["channels"]
                continue
            np.testing.assert_array_equal(a, exr["channels"][f"{name}.{q}"])
            compared += 1
    assert compared == (8 if method == "path-tracer" else 6)


def test_same_seed_same_images_at_any_thread_count_and_another_seed_differs(scene_dict):
    scene = obscura.Scene.from_dict(scene_dict)
    kw = dict(method="path-tracer", seed=3)
    one = obscura.render(scene, threads=1, **kw)["ir"].bands["mwir"].radiance
    two = obscura.render(scene, threads=2, **kw)["ir"].bands["mwir"].radiance
    np.testing.assert_array_equal(one, two)
    other = obscura.render(scene, method="path-tracer", seed=4)["ir"].bands["mwir"].radiance
    assert not np.array_equal(one, other)
    # The overrides lasted one call: the scene's own settings are back.
    assert scene.settings["method"] == "emission-absorption" and scene.settings["seed"] == 1


def test_a_scene_with_an_adaptive_threshold_renders_with_a_monte_carlo_method(scene_dict):
    scene_dict["render"].update({"samples_per_pixel": 4, "adaptive_threshold": 0.05})
    scene = obscura.Scene.from_dict(scene_dict)
    adaptive = obscura.render(scene)["ir"]
    spp = np.asarray(adaptive.samples_per_pixel)
    assert set(np.unique(spp)) == {1, 4}  # the cloud's edges refined, the clear sky not
    # The path tracer for one call leaves the threshold unused, then it is back.
    traced = obscura.render(scene, method="path-tracer", seed=3)["ir"]
    assert (np.asarray(traced.samples_per_pixel) == 4).all()
    assert scene.settings["adaptive_threshold"] == 0.05
    np.testing.assert_array_equal(np.asarray(obscura.render(scene)["ir"].samples_per_pixel), spp)


def test_progress_counts_the_photons_before_the_rows(scene_dict):
    # The radiance cache traces each spectral node's photons before any row:
    # 2 bands × 2 nodes × 5000 photons, reported in chunks.
    scene_dict["render"] = {"method": "radiance-cache", "seed": 1, "spectral_nodes_per_band": 2,
                            "radiance_cache": {"photons": 5000}}
    scene = obscura.Scene.from_dict(scene_dict)
    seen = []
    obscura.render(scene, progress=seen.append, threads=2)
    photons = [p for p in seen if p["sensor"] is None]
    assert photons and seen[:len(photons)] == photons  # before the rows
    assert all(p["photons_total"] == 4 * 5000 for p in photons)
    done = [p["photons_done"] for p in photons]
    assert done == sorted(done) and done[-1] == 4 * 5000
    assert seen[-1]["rows_done"] == seen[-1]["rows_total"] == 16

    class Stop(Exception):
        pass

    def stop_in_photons(p):
        if p["sensor"] is None:
            raise Stop()

    with pytest.raises(Stop):
        obscura.render(scene, progress=stop_in_photons)


def test_progress_is_reported_and_its_exception_stops_the_render(scene_dict):
    scene = obscura.Scene.from_dict(scene_dict)
    seen = []
    obscura.render(scene, progress=seen.append, threads=1)
    assert seen[-1]["rows_done"] == seen[-1]["rows_total"] == 16
    assert {p["sensor"] for p in seen} == {"ir"}

    class Stop(Exception):
        pass

    def stop(_):
        raise Stop()

    with pytest.raises(Stop):
        obscura.render(scene, progress=stop)


def test_bad_arguments_name_themselves(scene_dict):
    scene = obscura.Scene.from_dict(scene_dict)
    with pytest.raises(obscura.InputError, match=r"^sensors: no sensor 'tv' in the scene \(sensors: ir\)$"):
        obscura.render(scene, sensors=["tv"])
    with pytest.raises(obscura.InputError, match=r"^method: unknown render method 'mc'"):
        obscura.render(scene, method="mc")
    with pytest.raises(obscura.InputError, match=r"^threads: must lie in \[0, 4096\]"):
        obscura.render(scene, threads=-1)
    with pytest.raises(obscura.InputError, match=r"^time: must be a finite time in seconds$"):
        obscura.render(scene, time=float("inf"))
