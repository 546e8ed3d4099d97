"""Shared pieces of the Python tests: a small scene (a homogeneous cloud in
front of a hot target box) as a dict, and the CLI to compare against."""
import copy
import json
import os
import subprocess

import pytest

SMALL_SCENE = {
    "sensors": [{
        "name": "ir", "position": [0, -40, 3], "look_at": [0, 0, 1.5], "up": [0, 0, 1],
        "fov_deg": 20, "width": 24, "height": 16, "bands": ["mwir", "lwir"],
    }],
    "clouds": [{
        "type": "homogeneous", "min": [-1.5, -6, 0], "max": [0.5, -2, 4],
        "wavelengths_um": [4, 10], "sigma_a": [0.3, 0.2], "sigma_s": [0.2, 0.05],
        "g": [0.6, 0.4], "temperature": 300,
    }],
    "surfaces": [
        {"type": "ground", "name": "ground", "height": 0, "temperature": 288, "emissivity": 0.95},
        {"type": "box", "name": "target", "min": [-2, 0, 0], "max": [2, 4, 2.5],
         "temperature": 330, "emissivity": 0.9, "target": True},
    ],
    "sky": {"temperature": 250},
    "render": {"method": "emission-absorption", "seed": 1},
}


@pytest.fixture
def scene_dict():
    return copy.deepcopy(SMALL_SCENE)


@pytest.fixture
def cli():
    path = os.environ.get("OBSCURA_CLI")
    assert path and os.path.exists(path), "OBSCURA_CLI must name the built obscura tool"
    return path


def write_scene(tmp_path, doc, name="scene.json"):
    path = tmp_path / name
    path.write_text(json.dumps(doc))
    return path


def cli_error(cli, *args):
    """The message `obscura ARGS` prints after 'obscura: error: ' (it must fail)."""
    p = subprocess.run([cli, *map(str, args)], capture_output=True, text=True)
    assert p.returncode == 1, p.stdout + p.stderr
    prefix = "obscura: error: "
    line = [l for l in p.stderr.splitlines() if l.startswith(prefix)]
    assert line, p.stderr
    return line[0][len(prefix):]
