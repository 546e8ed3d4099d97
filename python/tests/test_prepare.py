"""obscura.prepare: a preparation configuration (a file or a dict) becomes
cloud keyframes and a manifest, as `obscura prepare` makes them."""
import json
import subprocess
from pathlib import Path

import pytest

import obscura
from conftest import cli_error

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "smoke-screen" / "prepare.json"


def small_config():
    """The smoke-screen example cut to three frames of 2 m voxels."""
    c = json.loads(EXAMPLE.read_text())
    c["dispersion"]["devices"] = c["dispersion"]["devices"][2:5]
    c["voxel_size_m"] = 2.0
    c["times_s"] = {"start": 0, "end": 6, "step": 3}
    return c


def info(cli, keyframe):
    p = subprocess.run([cli, "info", "--json", str(keyframe)], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    d = json.loads(p.stdout)
    return d["dims"], d["channels"], d["wavelengths_um"], d["time_s"]


def test_a_dict_prepares_the_cloud_the_cli_prepares(tmp_path, cli):
    config = small_config()
    (tmp_path / "prepare.json").write_text(json.dumps(config))
    lines = []
    r = obscura.prepare(config, tmp_path / "py", path=EXAMPLE, progress=lines.append)
    p = subprocess.run([cli, "prepare", str(tmp_path / "prepare.json"), "-o", str(tmp_path / "cli"),
                        "--json", "-q"], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    ref = json.loads(p.stdout)
    assert r["manifest"] == tmp_path / "py" / "cloud.json" and r["manifest"].exists()
    assert len(r["keyframes"]) == ref["keyframes"] == 3
    for key in ["times_s", "voxel_size_m", "material", "output_form", "wavelengths_um",
                "lifecycle", "released_mass_g", "warnings"]:
        assert r[key] == ref[key], key
    assert list(r["dims"]) == ref["dims"]
    assert any("keyframe 3 of 3" in line for line in lines)
    # The voxels are the CLI's: every channel's range and count of non-zero voxels.
    for k in r["keyframes"]:
        assert info(cli, k) == info(cli, tmp_path / "cli" / k.name)
    # The manifest reads back as the CLI's.
    assert json.loads(r["manifest"].read_text()) == json.loads(
        (tmp_path / "cli" / "cloud.json").read_text())


def test_a_file_is_read_relative_to_its_folder(tmp_path):
    config = small_config()
    config["times_s"] = {"start": 0, "end": 3, "step": 3}
    (tmp_path / "prepare.json").write_text(json.dumps(config))
    r = obscura.prepare(tmp_path / "prepare.json", tmp_path / "out")
    assert r["times_s"] == [0.0, 3.0] and all(k.exists() for k in r["keyframes"])


def test_bad_configurations_fail_with_the_clis_message(tmp_path, cli):
    config = small_config()
    config["voxel_size"] = 2  # a misspelt key
    path = tmp_path / "prepare.json"
    path.write_text(json.dumps(config))
    with pytest.raises(obscura.InputError) as e:
        obscura.prepare(config, tmp_path / "out", path=path)
    assert str(e.value) == cli_error(cli, "prepare", path, "-o", tmp_path / "out")
    assert e.value.field == "/voxel_size" and e.value.file == str(path)
    assert not (tmp_path / "out").exists()  # nothing half-written
    (tmp_path / "full").mkdir()
    (tmp_path / "full" / "x").write_text("")
    with pytest.raises(obscura.InputError, match="exists and is not an empty folder"):
        obscura.prepare(small_config(), tmp_path / "full", path=EXAMPLE)
    with pytest.raises(obscura.InputError, match="path: names the file a dict stands for"):
        obscura.prepare(path, tmp_path / "out", path=path)


def test_a_progress_callback_that_raises_stops_the_preparation(tmp_path):
    def stop(line):
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        obscura.prepare(small_config(), tmp_path / "out", path=EXAMPLE, progress=stop)
    assert list(tmp_path.iterdir()) == []  # no output, no temporary folder
