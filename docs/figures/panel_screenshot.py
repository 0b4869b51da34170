"""docs/panel.png: the viewer with its side panel on examples/live_params.py, under a private Xvfb.

    python docs/figures/panel_screenshot.py [--select drill]   (needs Xvfb and xdotool)
"""
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from PIL import ImageGrab

ROOT = Path(__file__).resolve().parents[2]
W, H = 1100, 600


def main() -> None:
    n = 700 + os.getpid() % 200
    while Path(f"/tmp/.X{n}-lock").exists():
        n += 1
    display = f":{n}"
    xvfb = subprocess.Popen(["Xvfb", display, "-screen", "0", f"{W}x{H}x24", "-nolisten", "tcp"])
    env = {**os.environ, "DISPLAY": display}
    tmp = Path(tempfile.mkdtemp())
    state = tmp / "state.json"
    time.sleep(1.0)
    view = subprocess.Popen([sys.executable, "-m", "sdfgl.cli", "view", str(ROOT / "examples" / "live_params.py"),
                             "--size", f"{W}x{H}", "--state-file", str(state), "--max-samples", "8",
                             "--aa", "1"], env=env)
    try:
        for _ in range(1200):
            time.sleep(0.25)
            try:
                st = json.loads(state.read_text())
            except (OSError, ValueError):
                continue
            if st["samples"] >= 8 and not st["compiling"]:
                break
        out = ROOT / "docs" / "panel.png"
        ImageGrab.grab(xdisplay=display).crop((0, 0, W, H)).save(out)
        print(f"wrote {out}")
    finally:
        view.kill()
        xvfb.kill()


if __name__ == "__main__":
    main()
