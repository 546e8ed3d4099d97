"""obscura: radiative transfer through obscurant clouds, from Python.

A thin layer over the C++ library (docs/python.md): scenes load through the
same loader as ``obscura render`` and fail with the same messages (as
``obscura.Error``), renders are the same calls and give the same images for
the same seed.
"""
import sys as _sys

from ._obscura import (  # noqa: F401  (the public names)
    Band,
    BandImage,
    Error,
    InputError,
    Scene,
    SensorImage,
    VoxelGrid,
    __version__,
    apparent_temperature,
    band_radiance,
    mie,
    planck,
    read_exr,
    render,
    write_keyframe,
)
from ._obscura import _render_sequence
from ._dataset import to_datasets as _to_datasets


def render_sequence(scene, times, *, method=None, threads=None, seed=None, progress=None):
    """Renders ``scene`` at each of ``times`` (s, strictly increasing).

    Returns ``{sensor name: xarray.Dataset}`` with dims (time, band, y, x)
    and CF-1.10 attributes when xarray is importable, else the same content
    as ``{sensor name: dict of numpy arrays}`` (docs/python.md lists both).
    ``method``, ``threads`` and ``seed`` override the scene's settings for
    this call; ``progress(dict)`` is called as image rows complete.
    """
    raw = _render_sequence(scene, [float(t) for t in times], method, threads, seed, progress,
                           " ".join(_sys.argv) or "python")
    return _to_datasets(raw)


__all__ = [
    "Band", "BandImage", "Error", "InputError", "Scene", "SensorImage", "VoxelGrid",
    "apparent_temperature", "band_radiance", "mie", "planck", "read_exr", "render",
    "render_sequence", "write_keyframe",
]
