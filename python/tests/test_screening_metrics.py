"""obscura.screening_metrics: the figures of metrics.csv and summary.json
from a render, a render_sequence result or plain arrays, computed by the
library (docs/metrics.md)."""
import csv
import json
import subprocess

import numpy as np
import pytest

import obscura
from conftest import write_scene


def thickening_cloud(tmp_path, scene_dict):
    """The small scene with an animated cloud in front of the target whose
    absorption grows from keyframe to keyframe (0, 2, 4, 6 s), so that the
    target becomes screened part-way."""
    shape = (6, 4, 4)  # 1 m voxels over [-3, 3] x [-6, -2] x [0, 4]
    frames = []
    for i, sigma in enumerate([0.02, 0.3, 0.9, 1.5]):
        grid = obscura.VoxelGrid(
            sigma_a=np.full(shape + (2,), sigma), sigma_s=np.full(shape + (2,), 0.1 * sigma),
            g=np.full(shape + (2,), 0.5), temperature=np.full(shape, 300.0),
            wavelengths_um=[4.0, 10.0], origin=(-3.0, -6.0, 0.0), voxel_size_m=1.0)
        obscura.write_keyframe(tmp_path / f"k{i}.vdb", grid, time_s=2.0 * i)
        frames.append({"file": f"k{i}.vdb", "time": 2.0 * i})
    (tmp_path / "cloud.json").write_text(json.dumps({
        "keyframes": frames,
        "lifecycle": {"init_end": 2, "loop_start": 2, "loop_end": 2, "loop_wrap": 0,
                      "extinction_start": 3}}))
    scene_dict["clouds"] = [{"type": "animated", "manifest": "cloud.json", "activation": 0.5}]
    return write_scene(tmp_path, scene_dict)


def test_a_sequence_gives_the_clis_metrics_csv_and_series(tmp_path, scene_dict, cli):
    path = thickening_cloud(tmp_path, scene_dict)
    p = subprocess.run([cli, "render", str(path), "-o", str(tmp_path / "out"), "--time", "0:6:1"],
                       capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    with open(tmp_path / "out" / "metrics.csv") as f:
        expected = list(csv.DictReader(f))
    series = json.loads((tmp_path / "out" / "metrics.json").read_text())["series"]

    scene = obscura.Scene.load(path)
    m = obscura.screening_metrics(scene, obscura.render_sequence(scene, np.arange(7.0)))
    assert len(m["frames"]) == len(expected) == 14
    columns = {"target_radiance": "target_radiance_W_m-2_sr-1",
               "background_radiance": "background_radiance_W_m-2_sr-1",
               "target_apparent_temperature_k": "target_apparent_temperature_K",
               "background_apparent_temperature_k": "background_apparent_temperature_K",
               "delta_t_k": "delta_t_K"}
    for row, ref in zip(m["frames"], expected):
        assert (row["sensor"], row["band"]) == (ref["sensor"], ref["band"])
        for key, value in row.items():
            if key in ("sensor", "band"):
                continue
            # metrics.csv holds 9 significant digits, empty where undefined.
            text = "" if value is None else f"{value:.9g}"
            assert text == ref[columns.get(key, key)], (key, row["time_s"])
    assert m["series"] == [{k: v for k, v in s.items()} for s in series]
    lwir = [s for s in m["series"] if s["band"] == "lwir"][0]
    assert 0.5 < lwir["time_to_screen_s"] + 0.5 < 6  # measured from the activation


def test_one_render_is_one_frame_of_the_sequence(scene_dict):
    scene = obscura.Scene.from_dict(scene_dict)
    one = obscura.screening_metrics(scene, obscura.render(scene, time=1.0), time=1.0)
    seq = obscura.render_sequence(scene, [1.0])["ir"]
    assert [r["time_s"] for r in one["frames"]] == [1.0, 1.0]
    for b, row in enumerate(one["frames"]):
        assert row["transmittance_mean"] == seq.transmittance_mean.values[0, b]
        assert row["delta_t_k"] == seq.delta_t.values[0, b]
    assert one["targets"][0]["target_pixels"] == int((seq.target_mask.values == 1).sum())


def test_arrays_give_the_closed_forms():
    rng = np.random.default_rng(3)
    t = rng.uniform(0, 0.2, size=(2, 12, 16)).astype(np.float32)  # (band, y, x)
    radiance = rng.uniform(1, 3, size=t.shape).astype(np.float32)
    target = np.zeros((12, 16), bool)
    target[3:7, 4:10] = True
    m = obscura.screening_metrics(transmittance=t, target=target, radiance=radiance,
                                  bands=["mwir", "lwir"], transmittance_threshold=0.1,
                                  background_margin_px=2)
    # Background: the target's box grown by 2 px, less the target.
    frame = np.zeros_like(target)
    frame[1:9, 2:12] = True
    background = frame & ~target
    for b, row in enumerate(m["frames"]):
        tt = t[b][target].astype(np.float64)
        assert row["transmittance_mean"] == pytest.approx(tt.mean(), rel=1e-12)
        for q in (10, 50, 90):  # numpy's default: Hyndman & Fan type 7, as the library's
            assert row[f"transmittance_p{q}"] == pytest.approx(np.percentile(tt, q), rel=1e-12)
        assert row["screened_fraction"] == np.mean(tt < 0.1)
        lt = radiance[b][target].astype(np.float64).mean()
        lb = radiance[b][background].astype(np.float64).mean()
        assert row["target_radiance"] == pytest.approx(lt, rel=1e-12)
        assert row["contrast"] == pytest.approx((lt - lb) / lb, rel=1e-12)
        band = ["mwir", "lwir"][b]
        dt = obscura.apparent_temperature(lt, band) - obscura.apparent_temperature(lb, band)
        assert row["delta_t_k"] == pytest.approx(float(dt), abs=0.05)  # 8 nodes vs accurate
    assert m["targets"][0]["background_pixels"] == background.sum()


def test_a_series_of_arrays_has_its_time_to_screen():
    # The screened fraction rises 0, 0.5, 1 over 0, 1, 2 s: the criterion
    # 0.9 is met where the line crosses it, at 1.8 s.
    t = np.ones((3, 1, 2, 2), np.float32)
    t[1, 0, 0, :] = 0.0
    t[2] = 0.0
    m = obscura.screening_metrics(transmittance=t, target=np.ones((2, 2), bool), bands="lwir",
                                  times=[0, 1, 2])
    assert [r["screened_fraction"] for r in m["frames"]] == [0.0, 0.5, 1.0]
    assert m["series"][0]["time_to_screen_s"] == pytest.approx(1.8)
    assert m["frames"][0]["target_radiance"] is None  # no radiance given


def test_bad_arrays_are_named():
    t = np.ones((4, 4), np.float32)
    with pytest.raises(obscura.InputError, match="^target: expected a \\(y, x\\) array"):
        obscura.screening_metrics(transmittance=t, target=np.ones((3, 4)), bands="lwir")
    with pytest.raises(obscura.InputError, match="^bands: give the bands"):
        obscura.screening_metrics(transmittance=t, target=np.ones((4, 4)))
    with pytest.raises(obscura.InputError, match="^times: give the time"):
        obscura.screening_metrics(transmittance=np.ones((2, 1, 4, 4)), target=np.ones((4, 4)),
                                  bands="lwir")
    with pytest.raises(obscura.InputError, match="^radiance: shape"):
        obscura.screening_metrics(transmittance=t, target=np.ones((4, 4)), bands="lwir",
                                  radiance=np.ones((4, 5)))
    with pytest.raises(obscura.InputError, match="^transmittance_threshold: must lie in"):
        obscura.screening_metrics(transmittance=t, target=np.ones((4, 4)), bands="lwir",
                                  transmittance_threshold=2)


def test_spectral_nodes_per_band_takes_a_count_per_band():
    # The LWIR (flat 8-12 um) as one node renders it: the Gauss node at 10 um
    # with weight 4 um. Its own count inverts it to the surfaces' 330 and
    # 290 K; the 8 nodes given to the other bands would not.
    target = np.zeros((4, 4), bool)
    target[1:3, 1:3] = True
    t = np.ones((1, 4, 4), np.float32)
    radiance = np.where(target, 4.0 * obscura.planck(10.0, 330.0),
                        4.0 * obscura.planck(10.0, 290.0)).astype(np.float32)[None]
    kw = dict(transmittance=t, target=target, radiance=radiance, bands=["lwir"],
              background_margin_px=1)
    m = obscura.screening_metrics(spectral_nodes_per_band={"*": 8, "lwir": 1}, **kw)
    assert m["frames"][0]["delta_t_k"] == pytest.approx(40.0, abs=2e-3)
    m = obscura.screening_metrics(spectral_nodes_per_band=8, **kw)
    assert m["frames"][0]["delta_t_k"] != pytest.approx(40.0, abs=0.05)
    with pytest.raises(obscura.InputError, match="^spectral_nodes_per_band/lwir: must lie in"):
        obscura.screening_metrics(spectral_nodes_per_band={"lwir": 0}, **kw)
