"""obscura.VoxelGrid from numpy arrays: shapes and dtypes checked with the
argument named, values by the library, written as a keyframe that a scene
renders."""
import numpy as np
import pytest

import obscura
from conftest import write_scene


def arrays(nx=4, ny=3, nz=2, nw=2):
    return dict(sigma_a=np.full((nx, ny, nz, nw), 0.2), sigma_s=np.full((nx, ny, nz, nw), 0.1),
                g=np.full((nx, ny, nz, nw), 0.5), temperature=np.full((nx, ny, nz), 300.0),
                wavelengths_um=[4.0, 10.0][:nw], origin=(-2.0, -1.5, 0.0), voxel_size_m=1.0)


def test_a_grid_keeps_its_shape_and_placement():
    g = obscura.VoxelGrid(**arrays())
    assert g.shape == (4, 3, 2)
    assert g.wavelengths_um == [4.0, 10.0]
    assert g.origin == (-2.0, -1.5, 0.0) and g.voxel_size_m == 1.0


def test_wrong_shapes_and_dtypes_are_named():
    a = arrays()
    a["sigma_s"] = np.zeros((4, 3, 2, 3))
    with pytest.raises(obscura.InputError, match=r"^VoxelGrid: sigma_s: has shape \(4, 3, 2, 3\), expected \(4, 3, 2, 2\)"):
        obscura.VoxelGrid(**a)
    a = arrays()
    a["temperature"] = np.zeros((4, 3), dtype=np.float32)
    with pytest.raises(obscura.InputError, match=r"^VoxelGrid: temperature: has shape \(4, 3\), expected \(nx, ny, nz\)"):
        obscura.VoxelGrid(**a)
    a = arrays()
    a["g"] = np.zeros((4, 3, 2, 2), dtype=np.int64)
    with pytest.raises(obscura.InputError, match=r"^VoxelGrid: g: has dtype int64, expected a floating-point array"):
        obscura.VoxelGrid(**a)
    a = arrays()
    a["voxel_size_m"] = 0.0
    with pytest.raises(obscura.InputError, match=r"^VoxelGrid: voxel_size_m: must be a finite length > 0"):
        obscura.VoxelGrid(**a)


def test_bad_values_are_named_by_channel_and_voxel():
    a = arrays()
    a["sigma_a"][1, 2, 0, 1] = -1.0
    with pytest.raises(obscura.InputError, match=r"sigma_a_001 voxel \(1,2,0\)"):
        obscura.VoxelGrid(**a)


def test_a_written_keyframe_renders_like_the_same_homogeneous_box(tmp_path, scene_dict):
    # A uniform grid filling the homogeneous cloud's box exactly (the medium
    # fills the grid's cells, values clamped in the outer half voxel:
    # docs/formats.md), so both scenes hold the same medium.
    box = scene_dict["clouds"][0]
    nx, ny, nz = 2, 4, 4  # 1 m voxels over [-1.5, 0.5] x [-6, -2] x [0, 4]
    g = obscura.VoxelGrid(
        sigma_a=np.broadcast_to(np.array(box["sigma_a"], float), (nx, ny, nz, 2)).copy(),
        sigma_s=np.broadcast_to(np.array(box["sigma_s"], float), (nx, ny, nz, 2)).copy(),
        g=np.broadcast_to(np.array(box["g"], float), (nx, ny, nz, 2)).copy(),
        temperature=np.full((nx, ny, nz), 300.0), wavelengths_um=[4.0, 10.0],
        origin=tuple(box["min"]), voxel_size_m=1.0)
    box_images = obscura.render(obscura.Scene.from_dict(scene_dict))
    obscura.write_keyframe(tmp_path / "box.vdb", g)
    scene_dict["clouds"] = [{"type": "vdb", "file": "box.vdb"}]
    images = obscura.render(obscura.Scene.load(write_scene(tmp_path, scene_dict)))
    for band in ("mwir", "lwir"):
        t = images["ir"].bands[band].transmittance
        assert t.min() < 0.9 and t.max() == 1.0
        np.testing.assert_allclose(t, box_images["ir"].bands[band].transmittance, rtol=1e-4)
        np.testing.assert_allclose(images["ir"].bands[band].radiance,
                                   box_images["ir"].bands[band].radiance, rtol=1e-4)
