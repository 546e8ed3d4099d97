#!/usr/bin/env python3
"""A demo frame through a fast method against a converged path-traced reference.

Prepares the demo's cloud once, renders the frame at --time with the path
tracer at --reference-spp (kept in --reference-file when given, reused when
its size, time and spp match) and with --method (default the radiance
cache), then prints per sensor and band: the target region's mean radiance
(the screening metrics' target_radiance) of both and their relative
difference, and the relative RMS difference after a 4x4 box blur over pixels
whose blurred reference is above 1 % of its largest (the radiance-cache
issue's measures), with the times. Beside the RMSE: the reference's own
noise on the same measure (the RMS over those pixels of the blurred
reference's relative standard error), which the RMSE includes in
quadrature. Nothing is asserted (docs/performance.md, docs/validation.md).

    PYTHONPATH=build/release/python /usr/bin/python3 bench/demo_accuracy.py \
        [--size 64x32] [--time 8] [--reference-spp 1024] [--reference-file F]
        [--method radiance-cache|photonmap] [--photons N] [--photons-by-band BAND=N,...]
        [--spp 4] [--adaptive-threshold T] [--sh-degree D]
        [--estimate tracks|collisions]
        [--voxel M] [--kernel-radius R] [--seed N] [--nodes-by-band BAND=N,...]
        [--no-sensor-peaks] [--save F]
"""
import argparse
import pathlib
import tempfile
import time

import numpy as np

import obscura
from demo_scene import prepare_demo


def blur4(image):
    h, w = image.shape[0] // 4 * 4, image.shape[1] // 4 * 4
    return image[:h, :w].reshape(h // 4, 4, w // 4, 4).mean(axis=(1, 3))


def target_radiance(scene, result, at):
    rows = obscura.screening_metrics(scene, result, time=at)["frames"]
    return {(r["sensor"], r["band"]): r["target_radiance"] for r in rows}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", default="64x32")
    parser.add_argument("--time", type=float, default=8.0)
    parser.add_argument("--reference-spp", type=int, default=1024)
    parser.add_argument("--reference-file")
    parser.add_argument("--method", default="radiance-cache")
    parser.add_argument("--photons", type=int, default=0)
    parser.add_argument("--photons-by-band", default="",
                        help="radiance cache: BAND=N[,BAND=N...], the photons per node of those "
                             "bands (/render/radiance_cache/photons)")
    # Four stratified samples per pixel by default: the reference is each
    # pixel's mean, which one sample at the pixel's centre is not where an
    # edge (the horizon, the cloud's rim) crosses it (docs/validation.md).
    parser.add_argument("--spp", type=int, default=4,
                        help="the method's samples per pixel (default 4)")
    parser.add_argument("--adaptive-threshold", type=float, default=0.0,
                        help="the method's /render/adaptive_threshold (the spp samples only "
                             "where a neighbouring pixel's centre differs by more)")
    parser.add_argument("--sh-degree", type=int, default=0)
    parser.add_argument("--estimate", default="")
    parser.add_argument("--voxel", type=float, default=0.0)
    parser.add_argument("--kernel-radius", type=int, default=0,
                        help="radiance cache: the splat's tent half-width, lattice spacings")
    parser.add_argument("--seed", type=int, default=0, help="the method's seed (default: the scene's)")
    parser.add_argument("--nodes-by-band", default="",
                        help="BAND=N[,BAND=N...]: the method's spectral nodes of those bands "
                             "(/render/spectral_nodes_per_band; the reference keeps the scene's)")
    parser.add_argument("--no-sensor-peaks", action="store_true",
                        help="radiance cache: the harmonics alone, no forward peak towards the sensors")
    parser.add_argument("--threads", type=int, default=0)
    parser.add_argument("--save", help="keep the method's band images (and the reference's) "
                                       "in this .npz file, keyed sensor/band")
    parser.add_argument("--root", default=".", help="the repository root")
    args = parser.parse_args()
    width, height = (int(v) for v in args.size.split("x"))
    root = pathlib.Path(args.root)

    with tempfile.TemporaryDirectory(prefix="obscura_accuracy_") as tmp:
        tmp = pathlib.Path(tmp)
        doc = prepare_demo(root, tmp, width, height)
        # The scene's method and the settings that belong to one method are
        # set below per render; the rest (nodes per band, seed) stay.
        render = {k: v for k, v in doc["render"].items()
                  if k not in ("method", "photon_map", "radiance_cache", "adaptive_threshold")}

        def scene_for(method, spp, extra):
            d = dict(doc, render=dict(render, method=method, samples_per_pixel=spp, **extra))
            return obscura.Scene.from_dict(d, path=str(tmp / "scene.json"))

        key = f"{width}x{height} t={args.time} spp={args.reference_spp}"
        reference, reference_stderr, reference_targets, reference_s = None, None, None, 0.0
        if args.reference_file and pathlib.Path(args.reference_file).exists():
            kept = np.load(args.reference_file, allow_pickle=True)
            # Files from before the standard errors were kept are made again.
            if str(kept["key"]) == key and "radiance_stderr" in kept:
                reference = kept["radiance"].item()
                reference_stderr = kept["radiance_stderr"].item()
                reference_targets = kept["targets"].item()
                reference_s = float(kept["seconds"])
        if reference is None:
            scene = scene_for("path-tracer", args.reference_spp, {})
            start = time.perf_counter()
            result = obscura.render(scene, time=args.time, threads=args.threads)
            reference_s = time.perf_counter() - start
            reference = {(s, b): np.array(result[s].bands[b].radiance, dtype=np.float64)
                         for s in result for b in result[s].bands}
            reference_stderr = {
                (s, b): np.array(result[s].bands[b].radiance_stderr, dtype=np.float64)
                for s in result for b in result[s].bands}
            reference_targets = target_radiance(scene, result, args.time)
            if args.reference_file:
                np.savez(args.reference_file, key=key, radiance=reference,
                         radiance_stderr=reference_stderr, targets=reference_targets,
                         seconds=reference_s)

        extra = {}
        if args.nodes_by_band:
            nodes = render.get("spectral_nodes_per_band", 8)
            nodes = dict(nodes) if isinstance(nodes, dict) else {"*": nodes}
            for item in args.nodes_by_band.split(","):
                band, n = item.split("=")
                nodes[band] = int(n)
            extra["spectral_nodes_per_band"] = nodes
        if args.method == "radiance-cache":
            cache = {}
            if args.photons > 0:
                cache["photons"] = args.photons
            if args.photons_by_band:
                counts = {"*": args.photons} if args.photons > 0 else {}
                for item in args.photons_by_band.split(","):
                    band, n = item.split("=")
                    counts[band] = int(float(n))
                cache["photons"] = counts
            if args.sh_degree > 0:
                cache["sh_degree"] = args.sh_degree
            if args.estimate:
                cache["estimate"] = args.estimate
            if args.voxel > 0:
                cache["voxel_m"] = args.voxel
            if args.kernel_radius > 0:
                cache["kernel_radius_nodes"] = args.kernel_radius
            if args.no_sensor_peaks:
                cache["sensor_peaks"] = False
            extra["radiance_cache"] = cache
        if args.method == "photonmap":
            # The demo's settings until 2026-12-07 (docs/demo.md): k = 30.
            extra["photon_map"] = {"photons": args.photons or 200000, "k": 30}
        if args.seed:
            extra["seed"] = args.seed
        if args.adaptive_threshold > 0:
            extra["adaptive_threshold"] = args.adaptive_threshold
        scene = scene_for(args.method, args.spp, extra)
        start = time.perf_counter()
        result = obscura.render(scene, time=args.time, threads=args.threads)
        seconds = time.perf_counter() - start
        targets = target_radiance(scene, result, args.time)
        if args.save:
            np.savez(args.save, **{f"{s}/{b}": np.array(result[s].bands[b].radiance)
                                   for s in result for b in result[s].bands},
                     **{f"reference/{s}/{b}": v for (s, b), v in reference.items()})

        print(f"demo frame at t = {args.time} s, {width}x{height} px; reference: path tracer, "
              f"{args.reference_spp} spp, {reference_s:.1f} s; {args.method}: {seconds:.2f} s")
        print(f"{'sensor':12} {'band':10} {'target ref':>11} {'target':>11} {'diff':>8} "
              f"{'RMSE (4x4)':>11} {'ref noise':>10} {'refined':>8}")
        for (sensor, band), ref in reference.items():
            got = np.array(result[sensor].bands[band].radiance, dtype=np.float64)
            a, b = blur4(ref), blur4(got)
            keep = a > 0.01 * a.max()
            rmse = np.sqrt(np.mean(((b - a)[keep] / a[keep]) ** 2))
            # The blurred pixel is the mean of 16 independent pixels: its
            # variance is the sum of theirs over 16².
            blurred_stderr = np.sqrt(blur4(reference_stderr[(sensor, band)] ** 2) / 16.0)
            ref_noise = np.sqrt(np.mean((blurred_stderr[keep] / a[keep]) ** 2))
            t_ref, t_got = reference_targets[(sensor, band)], targets[(sensor, band)]
            diff = t_got / t_ref - 1.0 if t_ref else float("nan")
            # The share of pixels that took more than one sample (all of them
            # without an adaptive threshold).
            refined = np.mean(np.array(result[sensor].samples_per_pixel) > 1)
            print(f"{sensor:12} {band:10} {t_ref:11.5g} {t_got:11.5g} {diff:8.4f} {rmse:11.4f} "
                  f"{ref_noise:10.4f} {refined:8.3f}")


if __name__ == "__main__":
    main()
