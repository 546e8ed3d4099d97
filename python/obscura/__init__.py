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
    optics,
    planck,
    read_exr,
    render,
    validate,
    write_keyframe,
)
from ._obscura import _prepare, _render_sequence, _study
from ._dataset import to_datasets as _to_datasets
from ._screening import screening_metrics  # noqa: F401


def _command_line():
    """What provenance records as the command: this Python program's."""
    return " ".join(_sys.argv) or "python"


def render_sequence(scene, times, *, method=None, threads=None, seed=None, progress=None):
    """Renders ``scene`` at each of ``times`` (s, strictly increasing).

    Returns ``{sensor name: xarray.Dataset}`` with dims (time, band, y, x)
    and CF-1.10 attributes when xarray is importable, else the same content
    as ``{sensor name: dict of numpy arrays}`` (docs/python.md lists both).
    ``method``, ``threads`` and ``seed`` override the scene's settings for
    this call; ``progress(dict)`` is called as image rows complete.
    """
    raw = _render_sequence(scene, [float(t) for t in times], method, threads, seed, progress,
                           _command_line())
    return _to_datasets(raw)


def prepare(config, out, *, path=None, threads=None, progress=None):
    """Prepares a cloud as ``obscura prepare CONFIG -o OUT`` does
    (docs/preparation.md): particle concentrations (the dispersion model, VTK
    or NetCDF-CF) and a material's optics become cloud keyframes and a
    manifest in the folder ``out``, which must not exist or be empty.

    ``config`` is a configuration file or a dict with its content; with a
    dict, ``path`` stands for the file (errors name it, relative paths in it
    resolve against its folder; default "prepare.json" in the current
    folder). ``progress(line)`` is called with each progress line. Returns
    what ``obscura prepare --json`` prints: manifest, keyframes, times_s,
    dims, voxel_size_m, material, wavelengths_um, lifecycle, warnings, ...
    """
    return _prepare(config, out, path, threads, progress, _command_line())


def study(config, out, *, path=None, threads=None, resume=False, progress=None):
    """Runs a parameter study as ``obscura study STUDY -o OUT`` does in one
    process (docs/studies.md): every case prepared, rendered and measured,
    the table written to ``out`` (results.csv, results.json, results.nc,
    screening.png). ``config`` is a study file or a dict with its content
    (``path`` as for ``prepare``). ``progress(line)`` is called as cases
    finish. Returns results.json's content, with ``files``: the paths
    written.
    """
    return _study(config, out, path, threads, resume, progress, _command_line())


__all__ = [
    "Band", "BandImage", "Error", "InputError", "Scene", "SensorImage", "VoxelGrid",
    "apparent_temperature", "band_radiance", "mie", "optics", "planck", "prepare", "read_exr",
    "render", "render_sequence", "screening_metrics", "study", "validate", "write_keyframe",
]
