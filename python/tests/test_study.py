"""obscura.study: a parameter study (a file or a dict) run into an output
folder as `obscura study` runs it, its results.json returned."""
import json
import subprocess
from pathlib import Path

import pytest

import obscura
from conftest import cli_error

EXAMPLES = Path(__file__).resolve().parents[2] / "examples" / "smoke-screen"


def tiny_study(folder):
    """The smoke-screen example cut down (two grenades, 2 m voxels, 48 x 24 px
    in the LWIR, the tank a target) over two wind directions."""
    prepare = json.loads((EXAMPLES / "prepare.json").read_text())
    devices = prepare["dispersion"]["devices"]
    prepare["dispersion"]["devices"] = [devices[3], devices[4]]
    prepare.update(times_s={"start": 0, "end": 8, "step": 2}, voxel_size_m=2.0,
                   wavelengths_um=[4.0, 10.0])
    (folder / "prepare.json").write_text(json.dumps(prepare))
    scene = json.loads((EXAMPLES / "scene.json").read_text())
    scene["sensors"][0].update(width=48, height=24, bands=["lwir"])
    scene["surfaces"][1]["target"] = True
    del scene["regions"]
    (folder / "scene.json").write_text(json.dumps(scene))
    return {"prepare": "prepare.json", "scene": "scene.json", "cloud": "screen",
            "times_s": {"start": 0, "end": 8, "step": 2},
            "axes": [{"name": "wind_from_deg", "file": "prepare",
                      "path": "/dispersion/wind/from_deg", "values": [250, 290]}]}


def comparable(cases):
    """The cases without what depends on where and when they ran (the
    fingerprint covers the case's documents, which name its output folder)."""
    return [{k: v for k, v in c.items() if k not in ("seconds", "rank", "fingerprint")}
            for c in cases]


def test_a_dict_study_gives_the_clis_results(tmp_path, cli):
    study = tiny_study(tmp_path)
    (tmp_path / "study.json").write_text(json.dumps(study))
    lines = []
    r = obscura.study(study, tmp_path / "py", path=tmp_path / "study.json", progress=lines.append)
    p = subprocess.run([cli, "study", str(tmp_path / "study.json"), "-o", str(tmp_path / "cli"),
                        "--json"], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    ref = json.loads(p.stdout)
    assert len(r["cases"]) == 2
    assert comparable(r["cases"]) == comparable(ref["cases"])
    assert r["axes"] == ref["axes"]
    series = r["cases"][0]["series"][0]
    assert series["sensor"] == "seeker" and series["time_to_screen_s"] > 0
    assert sorted(f.name for f in r["files"]) == sorted(
        ["results.csv", "results.json", "results.nc", "screening.png"])
    header = [(tmp_path / d / "results.csv").read_text().splitlines()[0] for d in ("py", "cli")]
    assert header[0] == header[1]
    assert any("case_0001 2/2 (wind_from_deg=290) done" in line for line in lines)
    # Resumed, nothing runs again.
    again = obscura.study(tmp_path / "study.json", tmp_path / "py", resume=True)
    assert [c["resumed"] for c in again["cases"]] == [True, True]
    assert comparable(again["cases"])[0]["series"] == comparable(r["cases"])[0]["series"]


def test_a_bad_study_fails_with_the_clis_message(tmp_path, cli):
    study = tiny_study(tmp_path)
    study["axes"][0]["path"] = "/dispersion/wind/from"
    path = tmp_path / "study.json"
    path.write_text(json.dumps(study))
    with pytest.raises(obscura.InputError) as e:
        obscura.study(study, tmp_path / "out", path=path)
    assert str(e.value) == cli_error(cli, "study", path, "-o", tmp_path / "out")
    assert not (tmp_path / "out").exists()
