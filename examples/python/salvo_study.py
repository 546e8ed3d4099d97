#!/usr/bin/env python3
"""Time to screen and screening duration against wind direction, in a
notebook's style.

The demo's scenario (examples/demo: eight smoke grenades on a 30 m arc in
front of a tank, four sensors 1 km away; the salvo of
examples/smoke-screen/prepare.json) with the wind turned over a few
directions: for each, the cloud is prepared (obscura.prepare), the demo scene
rendered over time at low resolution (obscura.render_sequence) and its
screening measured (obscura.screening_metrics); every sensor's time to
screen and screening duration are plotted against the wind direction with
matplotlib. The grenades burst in front of the tank, so the screen forms in
the same second whatever the wind; how long it holds depends on it.

    PYTHONPATH=build/release/python python3 examples/python/salvo_study.py -o out/salvo
    ... --winds 240,300 --size tiny     (the test's size: seconds)

The sweep renders with the path tracer at one sample per pixel: the screening
metrics use the line-of-sight transmittance, which every method computes
exactly, so a cheap render measures the same screening as the demo's radiance
cache. Writes screening.png and screening.csv into the output folder.
"""
import argparse
import csv
import json
import math
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402

import obscura  # noqa: E402

EXAMPLES = Path(__file__).resolve().parent.parent
# width, height (px), frame step and end (s), voxel size (m)
SIZES = {
    "tiny": {"width": 32, "height": 16, "step_s": 3.0, "end_s": 12.0, "voxel_m": 2.0},
    "low": {"width": 64, "height": 32, "step_s": 1.0, "end_s": 20.0, "voxel_m": 1.0},
}


def prepared_cloud(wind_from_deg, size, out):
    """The salvo's cloud with the wind from `wind_from_deg`, in `out`."""
    config = json.loads((EXAMPLES / "smoke-screen" / "prepare.json").read_text())
    config["dispersion"]["wind"]["from_deg"] = wind_from_deg
    config["voxel_size_m"] = size["voxel_m"]
    config["times_s"] = {"start": 0, "end": size["end_s"], "step": size["step_s"]}
    report = obscura.prepare(config, out, path=EXAMPLES / "smoke-screen" / "prepare.json")
    return Path(report["manifest"])


def demo_scene(manifest, size):
    """The demo scene with the prepared cloud, at the sweep's resolution."""
    scene = json.loads((EXAMPLES / "demo" / "scene.json").read_text())
    scene["clouds"][0]["manifest"] = str(manifest.resolve())
    for surface in scene["surfaces"]:
        if surface["type"] == "mesh":
            surface["file"] = str(EXAMPLES / "tank" / "tank.obj")
    for sensor in scene["sensors"]:
        sensor["width"], sensor["height"] = size["width"], size["height"]
    scene["render"] = {"method": "path-tracer", "samples_per_pixel": 1,
                       "spectral_nodes_per_band": 2, "seed": 1}
    return obscura.Scene.from_dict(scene, path=EXAMPLES / "demo" / "scene.json")


def screening(wind_from_deg, size, out):
    """{sensor: (time to screen, screening duration)} (s; NaN: never screened)."""
    scene = demo_scene(prepared_cloud(wind_from_deg, size, out / f"cloud_{wind_from_deg:g}"), size)
    n = int(round(size["end_s"] / size["step_s"]))
    times = [i * size["step_s"] for i in range(n + 1)]
    metrics = obscura.screening_metrics(scene, obscura.render_sequence(scene, times))
    def seconds(v):
        return math.nan if v is None else v

    return {s["sensor"]: (seconds(s["time_to_screen_s"]), seconds(s["screening_duration_s"]))
            for s in metrics["series"]}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", type=Path, default=Path("out/salvo"))
    parser.add_argument("--winds", default="180,225,270,315,360",
                        help="wind directions (degrees the wind comes from), comma-separated")
    parser.add_argument("--size", choices=sorted(SIZES), default="low")
    args = parser.parse_args(argv)
    winds = [float(w) for w in args.winds.split(",")]
    size = SIZES[args.size]
    args.output.mkdir(parents=True, exist_ok=True)

    results = {}
    for wind in winds:
        results[wind] = screening(wind, size, args.output)
        print(f"wind from {wind:g} deg: " + ", ".join(
            f"{sensor} screened after {t:.2f} s for {d:.2f} s"
            for sensor, (t, d) in results[wind].items()), flush=True)

    sensors = list(results[winds[0]])
    with open(args.output / "screening.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["wind_from_deg"] + [f"{s}_{q}_s" for s in sensors
                                        for q in ("time_to_screen", "screening_duration")])
        for wind in winds:
            w.writerow([wind] + [v for s in sensors for v in results[wind][s]])

    fig, axes = plt.subplots(1, 2, figsize=(10, 4), dpi=100)
    for i, label in enumerate(["time to screen (s)", "screening duration (s)"]):
        for sensor in sensors:
            axes[i].plot(winds, [results[w][sensor][i] for w in winds], marker="o", label=sensor)
        axes[i].set_xlabel("wind from (deg)")
        axes[i].set_ylabel(label)
        axes[i].grid(True, alpha=0.3)
    axes[0].legend()
    fig.suptitle("8-grenade salvo in front of the tank, against the wind's direction")
    fig.tight_layout()
    fig.savefig(args.output / "screening.png")
    print(f"wrote {args.output / 'screening.png'} and {args.output / 'screening.csv'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
