"""Ctrl-C during a render: the render stops at the next image row with
KeyboardInterrupt (the GIL is released, so the signal is seen at once), and
the scene renders again afterwards."""
import os
import subprocess
import sys
import textwrap

from conftest import SMALL_SCENE

SCRIPT = textwrap.dedent("""
    import json, os, signal, sys, threading, time
    import obscura
    doc = json.loads(sys.argv[1])
    doc["sensors"][0].update(width=320, height=240)
    doc["render"].update(method="path-tracer", samples_per_pixel=64)
    scene = obscura.Scene.from_dict(doc)
    sent = []
    def interrupt():
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)
    threading.Timer(1.0, interrupt).start()
    start = time.monotonic()
    try:
        obscura.render(scene, threads=2)
        print("finished", time.monotonic() - start)
    except KeyboardInterrupt:
        print("interrupted after", time.monotonic() - sent[0])
    small = obscura.render(scene, method="emission-absorption")
    print("again", small["ir"].width)
""")


def test_ctrl_c_interrupts_a_render_cleanly():
    p = subprocess.run([sys.executable, "-c", SCRIPT, __import__("json").dumps(SMALL_SCENE)],
                       capture_output=True, text=True, timeout=300, env=os.environ.copy())
    assert p.returncode == 0, p.stderr
    lines = p.stdout.splitlines()
    assert lines[0].startswith("interrupted after"), p.stdout
    assert float(lines[0].split()[-1]) < 2.0, p.stdout  # rows take milliseconds
    assert lines[1] == "again 320"
