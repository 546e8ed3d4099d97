"""render.nc, written by `obscura render --format netcdf`, opened with
xarray.open_dataset (the netCDF4 backend, Debian python3-netcdf4): one Dataset
with per-sensor dimensions, CF attributes, and the same values as the EXR
files and as obscura.render_sequence."""
import json
import subprocess

import netCDF4  # noqa: F401  xarray's netCDF-4 backend (Debian python3-netcdf4, scripts/install-deps)
import numpy as np
import pytest
import xarray as xr

import obscura
from conftest import write_scene


@pytest.fixture
def rendered(tmp_path, cli, scene_dict):
    # A second sensor with another size and band set; its name is not a
    # netCDF-safe suffix as it stands ("tv-1" -> "tv_1").
    scene_dict["sensors"].append({
        "name": "tv-1", "position": [4, -40, 3], "look_at": [0, 0, 1.5], "up": [0, 0, 1],
        "fov_deg": 25, "width": 8, "height": 6, "bands": ["lwir"]})
    path = write_scene(tmp_path, scene_dict)
    out = tmp_path / "out"
    subprocess.run([cli, "render", str(path), "-o", str(out), "--time", "0:1:1",
                    "--format", "netcdf"], check=True, capture_output=True)
    with xr.open_dataset(out / "render.nc") as ds:
        ds.load()
    return path, out, ds


def test_one_dataset_with_per_sensor_dimensions_and_cf_attributes(rendered):
    _, _, ds = rendered
    assert ds.attrs["Conventions"] == "CF-1.10"
    assert ds.attrs["source"] == f"obscura {obscura.__version__}"
    assert ds.attrs["run_status"] == "complete"
    assert "--format netcdf" in json.loads(ds.attrs["provenance"])["command_line"]
    assert json.loads(ds.attrs["sensors"]) == [{"name": "ir", "suffix": "ir"},
                                               {"name": "tv-1", "suffix": "tv_1"}]
    assert ds.radiance_ir.dims == ("time", "band_ir", "y_ir", "x_ir")
    assert ds.radiance_ir.shape == (2, 2, 16, 24)
    assert ds.apparent_temperature_tv_1.shape == (2, 1, 6, 8)
    np.testing.assert_array_equal(ds.time.values, [0.0, 1.0])
    assert list(ds.band_ir.values) == ["mwir", "lwir"]
    np.testing.assert_array_equal(ds.band_min_um_ir.values, [3.0, 8.0])
    np.testing.assert_array_equal(ds.band_max_um_ir.values, [5.0, 12.0])
    assert ds.radiance_ir.attrs["units"] == "W m-2 sr-1"
    assert ds.transmittance_ir.attrs["units"] == "1"
    assert ds.apparent_temperature_ir.attrs["units"] == "K"
    assert ds.apparent_temperature_ir.attrs["standard_name"] == "brightness_temperature"
    assert ds.radiance_tv_1.attrs["sensor"] == "tv-1"
    assert "radiance_stderr_ir" not in ds  # emission-absorption: no standard errors
    assert ds.target_mask_ir.attrs["flag_meanings"] == "other target background"
    assert ds.delta_t_ir.dims == ("time", "band_ir")
    assert ds.delta_t_ir.attrs["units"] == "K"


def test_values_equal_the_exr_files_and_render_sequence(rendered):
    path, out, ds = rendered
    for frame in (0, 1):
        exr = obscura.read_exr(out / f"ir_f{frame:04d}.exr")
        assert exr["attributes"]["obscura.time_s"] == float(frame)  # a number, not text
        for band in ("mwir", "lwir"):
            for q in ("radiance", "transmittance", "apparent_temperature"):
                np.testing.assert_array_equal(
                    ds[f"{q}_ir"].sel(band_ir=band).isel(time=frame).values,
                    exr["channels"][f"{band}.{q}"])
    mine = obscura.render_sequence(obscura.Scene.load(path), [0.0, 1.0])
    np.testing.assert_array_equal(ds.radiance_ir.values, mine["ir"].radiance.values)
    np.testing.assert_array_equal(ds.transmittance_tv_1.values, mine["tv-1"].transmittance.values)
    np.testing.assert_array_equal(ds.target_mask_ir.values, mine["ir"].target_mask.values)
    np.testing.assert_array_equal(ds.transmittance_mean_ir.values,
                                  mine["ir"].transmittance_mean.values)
    np.testing.assert_array_equal(ds.target_pixels_tv_1.values, mine["tv-1"].target_pixels.values)
