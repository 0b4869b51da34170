"""Frame times of the viewer at 1280x720 while orbiting and when idle: adaptive resolution on
and off, and the coarse pass on and off (idle figures, in alternating runs).

Starts its own Xvfb, opens `sdfgl view` on the demo scene (soft shadows, AO, the ground),
drags the mouse in circles with xdotool for a few seconds, then lets it settle. Run from the
repository root:

    python benchmarks/viewer_frametimes.py [rounds]
"""
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from tests.xserver import Driver, start_xvfb  # noqa: E402


DEMO = ("from sdfgl.demo import demo_camera, demo_scene\n"
        "scene, camera = demo_scene(), demo_camera()\n"
        "settings = {{'ground': True, 'coarse': {coarse}}}\n")


def measure(display: str, adaptive: bool, seconds: float = 6.0, coarse: bool = True) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        state = Path(tmp) / "state.json"
        scene = Path(tmp) / "demo.py"
        scene.write_text(DEMO.format(coarse=coarse))
        drv = Driver(display, state)
        args = [sys.executable, "-m", "sdfgl.cli", "view", str(scene), "--size", "1280x720", "--state-file", str(state),
                "--max-samples", "8"] + ([] if adaptive else ["--no-adaptive"])
        proc = subprocess.Popen(args, env=drv.env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        try:
            drv.find_window(60)
            drv.wait_for(lambda s: s["samples"] >= 8, timeout=120, what="first refinement")
            drv.xdo("mousemove", "--window", drv.window, "640", "360", "mousedown", "1")
            t0 = time.time()
            i = 0
            while time.time() - t0 < seconds:
                i += 1
                drv.xdo("mousemove", "--window", drv.window, str(640 + (i % 40) * 4), "360")
                time.sleep(0.01)
            drv.xdo("mouseup", "1")
            st = drv.wait_for(lambda s: not s["moving"] and s["samples"] >= 8, timeout=120, what="idle")
        finally:
            proc.terminate()
            proc.wait(10)
    log = st["frame_log"]
    moving = [(ms, sc) for mv, ms, sc in log if mv]
    idle = [ms for mv, ms, sc in log if not mv]
    return {"moving_ms": statistics.median(m for m, _ in moving[3:]) if len(moving) > 3 else float("nan"),
            "moving_scale": statistics.median(s for _, s in moving[3:]) if len(moving) > 3 else float("nan"),
            "moving_frames": len(moving), "idle_ms": statistics.median(idle[-8:]), "idle_frames": len(idle)}


def main() -> None:
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 1
    proc, display = start_xvfb()
    idle: dict[bool, list[float]] = {True: [], False: []}
    try:
        for _ in range(rounds):
            for adaptive, coarse in ((True, True), (False, True), (False, False)):
                r = measure(display, adaptive, coarse=coarse)
                if not adaptive:
                    idle[coarse].append(r["idle_ms"])
                print(f"adaptive {'on ' if adaptive else 'off'}, coarse pass {'on ' if coarse else 'off'}: orbiting "
                      f"{r['moving_ms']:.1f} ms/frame at {r['moving_scale']:.0%} resolution ({r['moving_frames']} "
                      f"frames); idle refinement {r['idle_ms']:.1f} ms per full-resolution sample")
        on, off = statistics.median(idle[True]), statistics.median(idle[False])
        print(f"idle full-resolution sample, median of {rounds}: coarse pass {on:.1f} ms, without {off:.1f} ms "
              f"({on / off:.2f}x)")
    finally:
        proc.terminate()


if __name__ == "__main__":
    main()
