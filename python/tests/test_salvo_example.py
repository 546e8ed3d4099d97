"""examples/python/salvo_study.py, the notebook-style example, at its tiny
size: two wind directions prepared, rendered and measured, the screening
plotted to a PNG and tabulated."""
import csv
import math
import struct
import subprocess
import sys
from pathlib import Path

SCRIPT = Path(__file__).resolve().parents[2] / "examples" / "python" / "salvo_study.py"


def test_the_salvo_study_plots_screening_against_the_wind(tmp_path):
    p = subprocess.run([sys.executable, str(SCRIPT), "-o", str(tmp_path), "--size", "tiny",
                        "--winds", "240,300"], capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stdout + p.stderr
    png = (tmp_path / "screening.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    assert struct.unpack(">II", png[16:24]) == (1000, 400)  # 10 x 4 in at 100 dpi
    with open(tmp_path / "screening.csv") as f:
        rows = list(csv.DictReader(f))
    assert [float(r["wind_from_deg"]) for r in rows] == [240.0, 300.0]
    for r in rows:
        for sensor in ["tv", "laser", "mwir_seeker", "lwir_seeker"]:
            t = float(r[f"{sensor}_time_to_screen_s"])
            d = float(r[f"{sensor}_screening_duration_s"])
            # The salvo screens the tank within the 12 s rendered, and holds.
            assert 0 <= t < 12 and 0 < d <= 12 - t + 1e-9, (r, sensor)
        assert f"wind from {float(r['wind_from_deg']):g} deg" in p.stdout
    # Each wind's cloud was prepared into its own folder.
    assert sorted(d.name for d in tmp_path.iterdir() if d.is_dir()) == ["cloud_240", "cloud_300"]
    assert not any(math.isnan(float(v)) for r in rows for v in r.values())
