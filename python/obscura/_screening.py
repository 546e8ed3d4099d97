"""obscura.screening_metrics: screening metrics (docs/metrics.md) of a
render, a render_sequence result, or plain arrays, computed by the library
(analysis/screening_metrics.h) as `obscura render` computes metrics.csv."""
import numpy as np

from ._obscura import Band, InputError, SensorImage, _scene_screening, _screening_metrics


def _input_error(field, detail):
    """obscura.InputError as the library raises it: "field: detail"."""
    e = InputError(f"{field}: {detail}")
    e.file, e.field, e.detail = "", field, detail
    return e


def _band(b):
    return b if isinstance(b, Band) else Band(str(b))


def _sequence_arrays(value):
    """(times, band names, transmittance, radiance) of one sensor's
    render_sequence result: an xarray.Dataset or its dict form."""
    if isinstance(value, dict):
        data, coords = value["data_vars"], value["coords"]
        return (np.asarray(coords["time"]["data"], dtype=float), list(coords["band"]["data"]),
                np.asarray(data["transmittance"]["data"]), np.asarray(data["radiance"]["data"]))
    return (value.time.values.astype(float), [str(b) for b in value.band.values],
            value.transmittance.values, value.radiance.values)


def _scene_inputs(scene, result, time):
    info = _scene_screening(scene)
    inputs = []
    sequences = {}
    for sensor, value in result.items():
        if sensor not in info["targets"]:
            raise _input_error("sensors", f"no sensor '{sensor}' in the scene")
        if isinstance(value, SensorImage):
            names = list(value.bands)
            inputs.append({
                "time_s": float(time), "sensor": sensor,
                "bands": [value.bands[n].band for n in names],
                "transmittance": np.stack([value.bands[n].transmittance for n in names]),
                "radiance": np.stack([value.bands[n].radiance for n in names]),
                "target": info["targets"][sensor]})
        else:
            sequences[sensor] = _sequence_arrays(value)
    # Frame by frame, every sensor in each: the order of metrics.csv.
    if sequences:
        frames = {len(v[0]) for v in sequences.values()}
        if len(frames) != 1:
            raise _input_error("result",
                               "the sensors' results have different numbers of frames")
        for i in range(frames.pop()):
            for sensor, (times, names, t, l) in sequences.items():
                by_name = {b.name: b for b in info["bands"][sensor]}
                inputs.append({
                    "time_s": float(times[i]), "sensor": sensor,
                    "bands": [by_name[n] for n in names], "transmittance": t[i],
                    "radiance": l[i], "target": info["targets"][sensor]})
    settings = {k: info[k] for k in ("transmittance_threshold", "screened_fraction",
                                     "background_margin_px", "spectral_nodes_per_band",
                                     "reference_time_s")}
    return inputs, settings


def _array_inputs(transmittance, target, radiance, bands, times, sensor):
    t = np.asarray(transmittance, dtype=np.float32)
    if t.ndim not in (2, 3, 4):
        raise _input_error("transmittance", f"expected (y, x), (band, y, x) or (time, band, y, "
                                            f"x), got {t.ndim} dimensions")
    shape = {2: (1, 1), 3: (1,), 4: ()}[t.ndim]
    t = t.reshape(shape + t.shape)
    l = None
    if radiance is not None:
        l = np.asarray(radiance, dtype=np.float32)
        if l.shape != np.shape(transmittance):
            raise _input_error("radiance", f"shape {l.shape} differs from transmittance's "
                                           f"{np.shape(transmittance)}")
        l = l.reshape(t.shape)
    if bands is None:
        raise _input_error("bands", "give the bands of the images (Band objects or names such "
                                    "as \"lwir\" or \"8:12\"), one per band of transmittance")
    bands = [_band(b) for b in ([bands] if isinstance(bands, (str, Band)) else bands)]
    if len(bands) != t.shape[1]:
        raise _input_error("bands", f"{len(bands)} bands for {t.shape[1]} images per frame")
    if times is None:
        if t.shape[0] != 1:
            raise _input_error("times", "give the time (s) of each of the frames")
        times = [0.0]
    times = [float(x) for x in np.atleast_1d(times)]
    if len(times) != t.shape[0]:
        raise _input_error("times", f"{len(times)} times for {t.shape[0]} frames")
    return [{"time_s": times[i], "sensor": sensor, "bands": bands, "transmittance": t[i],
             "radiance": None if l is None else l[i], "target": np.asarray(target)}
            for i in range(t.shape[0])]


def screening_metrics(scene=None, result=None, *, time=0.0, transmittance=None, target=None,
                      radiance=None, bands=None, times=None, sensor="sensor",
                      transmittance_threshold=0.05, screened_fraction=0.9,
                      background_margin_px=8, spectral_nodes_per_band=8, reference_time_s=0.0):
    """Screening metrics of rendered images (docs/metrics.md), computed by the
    library as ``obscura render`` computes metrics.csv and summary.json.

    * ``screening_metrics(scene, render(scene, ...), time=t)``: one frame;
    * ``screening_metrics(scene, render_sequence(scene, times))``: every frame,
      and the series (time to screen, screening duration);
    * ``screening_metrics(transmittance=T, target=mask, radiance=L, bands=[...],
      times=[...])``: arrays of shape (y, x), (band, y, x) or (time, band, y,
      x); ``target`` (y, x) is true on the target's pixels. Without
      ``radiance`` the radiance, contrast and temperature figures are NaN.

    With a scene, its target mask, bands and "metrics" settings are used;
    otherwise the keyword settings (the scene file's defaults);
    ``spectral_nodes_per_band`` is a count or ``{band: count, "*": count}``
    as in a scene file, the quadrature each band's radiance was rendered with. Returns a
    dict: ``frames`` (one row per frame, sensor and band, with metrics.json's
    keys: time_s, sensor, band, transmittance_mean, screened_fraction,
    contrast, delta_t_k, ...), ``series`` (per sensor and band:
    time_to_screen_s, screening_duration_s, ...), ``settings``, ``units`` and
    ``targets`` (pixel counts and bounding boxes).
    """
    if scene is not None:
        if result is None:
            raise _input_error("result", "give the result of render(scene) or "
                                         "render_sequence(scene, times)")
        inputs, s = _scene_inputs(scene, result, time)
    else:
        if transmittance is None or target is None:
            raise _input_error("transmittance", "give a scene and a render result, or "
                                                "transmittance= and target= arrays")
        inputs = _array_inputs(transmittance, target, radiance, bands, times, sensor)
        s = {"transmittance_threshold": transmittance_threshold,
             "screened_fraction": screened_fraction,
             "background_margin_px": background_margin_px,
             "spectral_nodes_per_band": spectral_nodes_per_band,
             "reference_time_s": reference_time_s}
    return _screening_metrics(inputs, **s)
