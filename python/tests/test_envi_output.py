"""<sensor>_fNNNN_radiance.img/.hdr, written by `obscura render --format
envi`, opened with GDAL's ENVI driver (Debian python3-gdal): one
band-sequential float cube per sensor and frame, with the band names, centre
wavelengths and widths in its header, and the same radiance as the EXR."""
import subprocess

import numpy as np
import pytest
from osgeo import gdal

import obscura
from conftest import write_scene

gdal.UseExceptions()


@pytest.fixture
def rendered(tmp_path, cli, scene_dict):
    path = write_scene(tmp_path, scene_dict)
    out = tmp_path / "out"
    subprocess.run([cli, "render", str(path), "-o", str(out), "--time", "0:1:1",
                    "--format", "envi"], check=True, capture_output=True)
    return out


def test_gdal_reads_each_frame_as_a_cube_with_the_exr_radiance(rendered):
    for frame in (0, 1):
        cube = gdal.Open(str(rendered / f"ir_f{frame:04d}_radiance.img"))
        assert cube.GetDriver().ShortName == "ENVI"
        assert (cube.RasterXSize, cube.RasterYSize, cube.RasterCount) == (24, 16, 2)
        exr = obscura.read_exr(rendered / f"ir_f{frame:04d}.exr")
        for i, band in enumerate(("mwir", "lwir"), start=1):
            values = cube.GetRasterBand(i).ReadAsArray()
            assert values.dtype == np.float32
            np.testing.assert_array_equal(values, exr["channels"][f"{band}.radiance"])


def test_the_header_gives_band_names_wavelengths_and_units(rendered):
    cube = gdal.Open(str(rendered / "ir_f0000_radiance.img"))
    envi = cube.GetMetadata("ENVI")
    assert envi["wavelength_units"] == "Micrometers"
    assert envi["data_units"] == "W m-2 sr-1"
    assert [float(w) for w in envi["wavelength"].strip("{}").split(",")] == [4.0, 10.0]
    assert [float(w) for w in envi["fwhm"].strip("{}").split(",")] == [2.0, 4.0]
    assert [b.strip() for b in envi["band_names"].strip("{}").split(",")] == ["mwir", "lwir"]
    band = cube.GetRasterBand(1)
    assert band.GetDescription() == "mwir (4 Micrometers)"
    assert band.GetMetadata() == {"wavelength": "4", "wavelength_units": "Micrometers"}
    # GDAL keeps no description; the header has it.
    header = (rendered / "ir_f0000_radiance.hdr").read_text()
    assert "description = {obscura band radiance, sensor ir, t = 0 s}" in header
