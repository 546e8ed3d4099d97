#!/usr/bin/env python3
"""Delta-M's truncation on a slab, apart from photon noise and the lattice.

The radiance cache's ray without a forward peak reads the in-scattered
radiance as f L(x, w) + sum_{l <= L} (g^l - f) sum_m Y_lm(w) L_lm(x), f = g^(L+1)
(delta-M, docs/physics.md), from the incident radiance's harmonics L_lm. This
script computes that reading in one dimension, with the harmonics exact: a
Monte Carlo walk in a laterally infinite Henyey-Greenstein slab (optical
thickness --tau, albedo --albedo, asymmetry --g) lit by a uniform sky (unit
radiance above the horizon, black below) tallies the Legendre moments
L_l(t) = int L(t, w) P_l(mu) dw of the radiance by track length in --bins
depth bins; then R, the flux reflectance, is integrated from the delta-M
reading along upward rays (the extinction sigma_t - f sigma_s, nothing from
below the slab) for each degree L, and from the whole series for the
truth. What it prints is the bias of the method at each degree, which the
cache's own `obscura validate slab --sh-degree L` measures with its photons
and its lattice (docs/validation.md). Nothing is asserted.

    /usr/bin/python3 bench/slab_delta_m_model.py [--tau 0.1] [--albedo 0.99] [--g 0.85]
        [--photons 2000000] [--bins 20] [--seed 1]
"""
import argparse

import numpy as np
from numpy.polynomial import legendre

MOMENTS = 40  # Legendre moments tallied; the whole series' R converges by then


def legendre_p(l, x):
    return legendre.legval(x, [0.0] * l + [1.0])


def sample_hg(rng, mu, g):
    """New direction cosines after scattering by HG(g) (the standard inversion)."""
    u = rng.random(len(mu))
    s = (1 - g * g) / (1 - g + 2 * g * u)
    cos_t = (1 + g * g - s * s) / (2 * g) if g != 0 else 2 * u - 1
    sin_t = np.sqrt(np.maximum(0.0, 1 - cos_t * cos_t))
    phi = 2 * np.pi * rng.random(len(mu))
    return mu * cos_t + np.sqrt(np.maximum(0.0, 1 - mu * mu)) * sin_t * np.cos(phi)


def moments(args):
    """L_l(t) per depth bin, for unit sky radiance (incident flux pi)."""
    rng = np.random.default_rng(args.seed)
    edges = np.linspace(0.0, args.tau, args.bins + 1)
    tally = np.zeros((MOMENTS, args.bins))
    mu = -np.sqrt(rng.random(args.photons))  # downward, cosine-weighted: a uniform sky
    depth = np.zeros(args.photons)
    weight = np.ones(args.photons)
    reflected = 0.0
    while len(mu):
        end = depth - mu * -np.log(rng.random(len(mu)))  # optical depth grows downward
        clipped = np.clip(end, 0.0, args.tau)
        lo, hi = np.minimum(depth, clipped), np.maximum(depth, clipped)
        p = np.array([legendre_p(l, mu) for l in range(MOMENTS)])
        for b in range(args.bins):
            track = np.clip(np.minimum(hi, edges[b + 1]) - np.maximum(lo, edges[b]), 0.0, None)
            tally[:, b] += p @ (track / np.abs(mu) * weight)
        up, down = end < 0.0, end > args.tau
        reflected += weight[up].sum()
        inside = ~(up | down)
        mu, depth, weight = mu[inside], end[inside], weight[inside] * args.albedo
        mu = sample_hg(rng, mu, args.g)
        alive = weight > 1e-4
        mu, depth, weight = mu[alive], depth[alive], weight[alive]
    width = args.tau / args.bins
    return tally * np.pi / args.photons / width, reflected / args.photons, edges


def reflectance(l_moments, edges, args, degree, delta_m):
    """R from the reading at `degree` (delta-M's or the plain truncation)."""
    g, a = args.g, args.albedo
    f = g ** (degree + 1) if delta_m and g > 0 else 0.0
    mu, w = legendre.leggauss(64)
    mu, w = 0.5 * (mu + 1), 0.5 * w  # upward cosines in (0, 1)
    depth = 0.5 * (edges[1:] + edges[:-1])
    width = edges[1] - edges[0]
    radiance = np.zeros(len(mu))
    for i, m in enumerate(mu):
        j = sum((2 * l + 1) / (4 * np.pi) * (g ** l - f) * l_moments[l] * legendre_p(l, m)
                for l in range(degree + 1))
        radiance[i] = (a / m * j * np.exp(-(1 - f * a) * depth / m) * width).sum()
    return 2.0 * (radiance * mu * w).sum()  # pi L / (pi L0), L0 = 1


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tau", type=float, default=0.1)
    parser.add_argument("--albedo", type=float, default=0.99)
    parser.add_argument("--g", type=float, default=0.85)
    parser.add_argument("--photons", type=int, default=2000000)
    parser.add_argument("--bins", type=int, default=20)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    l_moments, escaped, edges = moments(args)
    whole = reflectance(l_moments, edges, args, MOMENTS - 1, False)
    print(f"slab tau {args.tau}, albedo {args.albedo}, g {args.g}, uniform sky; "
          f"{args.photons} photons")
    print(f"R escaped through the top {escaped:.6f}, from the whole series {whole:.6f}")
    print("degree  plain truncation  delta-M   (relative to the whole series)")
    for degree in (2, 3, 4, 5, 6, 7):
        plain = reflectance(l_moments, edges, args, degree, False)
        scaled = reflectance(l_moments, edges, args, degree, True)
        print(f"{degree:6d}  {plain:.6f} {plain / whole - 1:+7.2%}  "
              f"{scaled:.6f} {scaled / whole - 1:+7.2%}")


if __name__ == "__main__":
    main()
