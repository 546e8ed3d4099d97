"""Scenes from Python: loaded from a file or a dict by the same loader as the
CLI, with the CLI's messages for bad input, and readable as Python objects."""
import json
import pathlib

import pytest

import obscura
from conftest import cli_error, write_scene

EXAMPLE = pathlib.Path(__file__).resolve().parents[2] / "examples" / "puff-over-target" / "scene.json"


def test_a_loaded_scene_shows_its_sensors_bands_and_settings(scene_dict):
    s = obscura.Scene.from_dict(scene_dict)
    assert [x["name"] for x in s.sensors] == ["ir"]
    assert (s.sensors[0]["width"], s.sensors[0]["height"]) == (24, 16)
    assert [b.name for b in s.bands["ir"]] == ["mwir", "lwir"]
    assert s.settings["method"] == "emission-absorption"
    assert s.settings["spectral_nodes_per_band"] == 8  # the default, filled in
    assert s.has_target
    assert s.to_dict() == json.loads(json.dumps(scene_dict))
    # A count per band comes back in the scene file's form.
    scene_dict["render"]["spectral_nodes_per_band"] = {"lwir": 1, "*": 4}
    s = obscura.Scene.from_dict(scene_dict)
    assert s.settings["spectral_nodes_per_band"] == {"*": 4, "lwir": 1}


def test_a_typo_gives_the_cli_message_from_a_file_and_from_a_dict(tmp_path, cli, scene_dict):
    scene_dict["render"]["sampels_per_pixel"] = 4
    path = write_scene(tmp_path, scene_dict, "typo.json")
    expected = cli_error(cli, "render", path, "-o", tmp_path / "out")
    assert "/render/sampels_per_pixel: unknown field" in expected
    with pytest.raises(obscura.InputError) as from_file:
        obscura.Scene.load(path)
    assert str(from_file.value) == expected
    with pytest.raises(obscura.InputError) as from_dict:
        obscura.Scene.from_dict(scene_dict, path=path)
    assert str(from_dict.value) == expected
    assert from_dict.value.field == "/render/sampels_per_pixel"
    assert not (tmp_path / "out").exists()


def test_an_out_of_range_value_names_the_json_path(scene_dict):
    scene_dict["sensors"][0]["fov_deg"] = 200
    with pytest.raises(obscura.Error, match=r"scene.json: /sensors/0/fov_deg: "):
        obscura.Scene.from_dict(scene_dict)


def test_a_missing_file_is_an_error_naming_it(tmp_path):
    with pytest.raises(obscura.Error, match="nothing.json"):
        obscura.Scene.load(tmp_path / "nothing.json")


def test_nan_is_not_json(scene_dict):
    scene_dict["sky"]["temperature"] = float("nan")
    with pytest.raises(ValueError):
        obscura.Scene.from_dict(scene_dict)


def test_relative_cloud_files_resolve_against_the_path_given(tmp_path):
    doc = json.loads(EXAMPLE.read_text())
    with pytest.raises(obscura.Error, match=str(tmp_path / "puff.vdb")):
        obscura.Scene.from_dict(doc, path=tmp_path / "scene.json")
