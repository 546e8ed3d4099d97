"""The demo scene (examples/demo) prepared for the Python benches: the
smoke-screen cloud prepared into a scratch folder beside the tank, and the
scene's dict with every sensor at the size asked for (bench/demo_accuracy.py,
bench/radiance_cache_noise.py)."""
import json
import pathlib

import obscura


def prepare_demo(root, folder, width, height):
    """Prepares the cloud and copies the tank into `folder`; returns the
    scene's dict, to be loaded with obscura.Scene.from_dict(doc,
    path=folder / "scene.json")."""
    root, folder = pathlib.Path(root), pathlib.Path(folder)
    obscura.prepare(str(root / "examples/smoke-screen/prepare.json"), str(folder / "cloud"))
    (folder / "tank.obj").write_bytes((root / "examples/tank/tank.obj").read_bytes())
    doc = json.loads((root / "examples/demo/scene.json").read_text())
    for sensor in doc["sensors"]:
        sensor["width"], sensor["height"] = width, height
    return doc
