"""Render docs/animation.gif: examples/pulse.py on a turntable, as a small GIF.

    python docs/figures/animation_gif.py [docs/animation.gif]
"""
import sys
from pathlib import Path

import sdfgl as sg
from sdfgl.scenefile import load_scene_file

HERE = Path(__file__).resolve().parent

if __name__ == "__main__":
    out = Path(sys.argv[1] if len(sys.argv) > 1 else HERE.parent / "animation.gif")
    sf = load_scene_file(HERE.parents[1] / "examples" / "pulse.py")
    cam = sf.camera
    res = sg.animate(sf.scene, out, seconds=4, fps=12, size=(320, 180), progress=True, aa=2, ground=True,
                     camera=sg.turntable(distance=cam.distance, pitch=cam.pitch, target=cam.target, yaw=cam.yaw))
    print(f"wrote {out}: {res.frames} frames, {out.stat().st_size / 1e6:.2f} MB, {res.compiles} compile(s)")
