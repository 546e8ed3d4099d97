#!/usr/bin/env python3
"""The radiance cache's photon noise on the demo frame against its cost.

Prepares the demo's cloud once, then renders the frame at --time with the
radiance cache for each estimate ("tracks", "collisions") and photon count,
twice with different seeds. The noise of one render is the RMS relative
difference between the two renders over pixels above 1 % of the image's
largest radiance, divided by sqrt(2); the time is the mean wall time of the
two renders (cache and march). Prints one row per sensor, estimate and
photon count. Nothing is asserted (docs/performance.md).

    PYTHONPATH=build/release/python python3 bench/radiance_cache_noise.py \
        [--size 256x128] [--time 8] [--photons 50000,100000,200000,400000] [--threads 0]
"""
import argparse
import pathlib
import tempfile
import time

import numpy as np

import obscura
from demo_scene import prepare_demo


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", default="256x128")
    parser.add_argument("--time", type=float, default=8.0)
    parser.add_argument("--photons", default="50000,100000,200000,400000")
    parser.add_argument("--estimates", default="tracks,collisions")
    parser.add_argument("--threads", type=int, default=0)
    parser.add_argument("--root", default=".", help="the repository root")
    args = parser.parse_args()
    width, height = (int(v) for v in args.size.split("x"))
    root = pathlib.Path(args.root)

    with tempfile.TemporaryDirectory(prefix="obscura_noise_") as tmp:
        tmp = pathlib.Path(tmp)
        doc = prepare_demo(root, tmp, width, height)
        doc["render"]["method"] = "radiance-cache"
        # One sample per pixel, as measured before the demo's scene took 4
        # where the image has an edge (docs/performance.md).
        for key in ("photon_map", "samples_per_pixel", "adaptive_threshold"):
            doc["render"].pop(key, None)
        print(f"demo frame at t = {args.time} s, {width}x{height} px per sensor, "
              f"threads {args.threads or 'all'}")
        print(f"{'sensor':12} {'estimate':10} {'photons':>8} {'seconds':>8} {'noise':>8}")
        for estimate in args.estimates.split(","):
            for photons in (int(p) for p in args.photons.split(",")):
                doc["render"]["radiance_cache"] = {"photons": photons, "estimate": estimate}
                scene = obscura.Scene.from_dict(doc, path=str(tmp / "scene.json"))
                renders, seconds = [], 0.0
                for seed in (1, 2):
                    start = time.perf_counter()
                    renders.append(obscura.render(scene, time=args.time, seed=seed,
                                                  threads=args.threads))
                    seconds += (time.perf_counter() - start) / 2
                for sensor in renders[0]:
                    for band in renders[0][sensor].bands:
                        a = np.asarray(renders[0][sensor].bands[band].radiance, dtype=np.float64)
                        b = np.asarray(renders[1][sensor].bands[band].radiance, dtype=np.float64)
                        keep = np.maximum(a, b) > 0.01 * max(a.max(), b.max())
                        mean = 0.5 * (a + b)[keep]
                        noise = np.sqrt(np.mean(((a - b)[keep] / mean) ** 2) / 2.0)
                        print(f"{sensor:12} {estimate:10} {photons:8d} {seconds:8.2f} "
                              f"{noise:8.4f}")


if __name__ == "__main__":
    main()
