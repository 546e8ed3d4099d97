"""What obscura.render_sequence returns: one xarray.Dataset per sensor with
CF-1.10 attributes (Conventions, units, long_name, standard_name where CF has
one), or, without xarray, the same variables as a dict of numpy arrays."""
import json

# name: (units, long_name, standard_name or None)
_IMAGE_VARIABLES = {
    "radiance": ("W m-2 sr-1", "band radiance at the sensor", None),
    "radiance_stderr": ("W m-2 sr-1", "standard error of the band radiance (Monte Carlo)", None),
    "transmittance": ("1", "line-of-sight transmittance of the clouds to the first surface", None),
    "apparent_temperature": ("K", "blackbody temperature with the band radiance",
                             "brightness_temperature"),
}

_METRIC_UNITS = {
    "target_pixels": ("1", "target pixels"),
    "background_pixels": ("1", "background pixels around the target"),
    "transmittance_mean": ("1", "mean line-of-sight transmittance over the target"),
    "transmittance_p10": ("1", "10th percentile of the target's transmittance"),
    "transmittance_p50": ("1", "median of the target's transmittance"),
    "transmittance_p90": ("1", "90th percentile of the target's transmittance"),
    "screened_fraction": ("1", "fraction of target pixels below the screening threshold"),
    "target_radiance": ("W m-2 sr-1", "mean band radiance of the target"),
    "background_radiance": ("W m-2 sr-1", "mean band radiance of the background"),
    "contrast": ("1", "Weber contrast of target against background"),
    "target_apparent_temperature": ("K", "apparent temperature of the target's mean radiance"),
    "background_apparent_temperature": ("K", "apparent temperature of the background's mean radiance"),
    "delta_t": ("K", "apparent temperature difference, target minus background"),
}


def _sensor_variables(raw, name):
    """(data_vars, coords, attrs) of one sensor, as plain numpy arrays."""
    s = raw["sensors"][name]
    dims = ("time", "band", "y", "x")
    data_vars = {}
    for var, (units, long_name, standard_name) in _IMAGE_VARIABLES.items():
        if s[var] is None:  # the standard error exists for Monte Carlo methods only
            continue
        attrs = {"units": units, "long_name": long_name}
        if standard_name:
            attrs["standard_name"] = standard_name
        data_vars[var] = (dims, s[var], attrs)
    if s["target_mask"] is not None:
        data_vars["target_mask"] = (("y", "x"), s["target_mask"], {
            "long_name": "target mask", "flag_values": [0, 1, 2],
            "flag_meanings": "other target background"})
        for var, values in s["metrics"].items():
            units, long_name = _METRIC_UNITS[var]
            data_vars[var] = (("time", "band"), values, {"units": units, "long_name": long_name})
    coords = {
        "time": ("time", raw["times_s"], {"units": "s", "long_name": "scene time", "axis": "T"}),
        "band": ("band", list(s["bands"]), {"long_name": "sensor band"}),
        "band_min_um": ("band", s["band_min_um"], {"units": "um", "long_name": "band lower limit"}),
        "band_max_um": ("band", s["band_max_um"], {"units": "um", "long_name": "band upper limit"}),
        "y": ("y", list(range(s["height"])), {"long_name": "image row, top first"}),
        "x": ("x", list(range(s["width"])), {"long_name": "image column, left first"}),
    }
    prov = raw["provenance"]
    attrs = {
        "Conventions": "CF-1.10",
        "title": f"obscura render of sensor {name}",
        "source": f"obscura {prov['version']}",
        "history": f"{prov['created_utc']}: {prov['command_line']}",
        "sensor": name,
        "method": raw["method"],
        "seed": raw["seed"],
        "provenance": json.dumps(prov, sort_keys=True),
        "scene": json.dumps(raw["scene"], sort_keys=True),
    }
    screening = [r for r in raw["screening"] if r["sensor"] == name]
    if screening:
        attrs["screening"] = json.dumps(screening, sort_keys=True)
    return data_vars, coords, attrs


def to_datasets(raw):
    """{sensor: xarray.Dataset} when xarray imports, else {sensor: dict}."""
    try:
        import xarray
    except ImportError:
        xarray = None
    out = {}
    for name in raw["sensors"]:
        data_vars, coords, attrs = _sensor_variables(raw, name)
        if xarray is not None:
            out[name] = xarray.Dataset(data_vars=data_vars, coords=coords, attrs=attrs)
        else:
            out[name] = {
                "dims": {"time": len(raw["times_s"]), "band": len(coords["band"][1]),
                         "y": len(coords["y"][1]), "x": len(coords["x"][1])},
                "data_vars": {k: {"dims": v[0], "data": v[1], "attrs": v[2]}
                              for k, v in data_vars.items()},
                "coords": {k: {"dims": (v[0],), "data": v[1], "attrs": v[2]}
                           for k, v in coords.items()},
                "attrs": attrs,
            }
    return out
