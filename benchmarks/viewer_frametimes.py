"""Frame times of the viewer at 1280x720 while orbiting and when idle, adaptive on and off.

Starts its own Xvfb, opens `sdfgl view` on the demo scene, drags the mouse in circles
with xdotool for a few seconds, then lets it settle. Run from the repository root:

    python benchmarks/viewer_frametimes.py
    python benchmarks/viewer_frametimes.py --coarse [ROUNDS]

``--coarse`` instead compares the idle full-resolution sample of the demo (soft shadows, AO,
the ground) with the coarse pass on and off, in interleaved rounds (default 3), no orbiting.
"""
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from tests.xserver import Driver, start_xvfb  # noqa: E402


def measure(display: str, adaptive: bool, seconds: float = 6.0) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        state = Path(tmp) / "state.json"
        drv = Driver(display, state)
        args = [sys.executable, "-m", "sdfgl.cli", "view", "--demo", "--size", "1280x720", "--state-file", str(state),
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


DEMO_FILE = """from sdfgl.demo import demo_camera, demo_scene
scene = demo_scene()
camera = demo_camera()
settings = {"shadows": "soft", "ao": True, "ground": True, "coarse": %r}
"""


def measure_idle(display: str, coarse: bool, samples: int = 8) -> list[float]:
    """Draw times (ms) of the idle full-resolution samples of the demo at 1280x720, coarse on or off."""
    with tempfile.TemporaryDirectory() as tmp:
        scene, state = Path(tmp) / "demo.py", Path(tmp) / "state.json"
        scene.write_text(DEMO_FILE % coarse)
        drv = Driver(display, state)
        args = [sys.executable, "-m", "sdfgl.cli", "view", str(scene), "--size", "1280x720", "--state-file",
                str(state), "--max-samples", str(samples), "--no-panel"]
        proc = subprocess.Popen(args, env=drv.env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        try:
            drv.find_window(60)
            st = drv.wait_for(lambda s: not s["moving"] and s["samples"] >= samples, timeout=300, what="refinement")
        finally:
            proc.terminate()
            proc.wait(10)
    assert st["coarse"] == (8 if coarse else 0), st["coarse"]
    return [ms for mv, ms, sc in st["frame_log"] if not mv][-(samples - 2):]  # the first samples warm up


def coarse_main(rounds: int) -> None:
    proc, display = start_xvfb()
    times: dict[bool, list[float]] = {True: [], False: []}
    try:
        for i in range(rounds):
            for coarse in ((True, False) if i % 2 == 0 else (False, True)):
                ms = measure_idle(display, coarse)
                times[coarse].extend(ms)
                print(f"round {i + 1} coarse {'on ' if coarse else 'off'}: median {statistics.median(ms):.1f} ms "
                      f"per sample ({len(ms)} samples)", flush=True)
    finally:
        proc.terminate()
    on, off = statistics.median(times[True]), statistics.median(times[False])
    print(f"viewer idle sample at 1280x720, demo with soft shadows + AO: coarse on {on:.1f} ms, off {off:.1f} ms, "
          f"on/off {on / off:.2f}x")


def main() -> None:
    if "--coarse" in sys.argv:
        rest = sys.argv[sys.argv.index("--coarse") + 1:]
        coarse_main(int(rest[0]) if rest else 3)
        return
    proc, display = start_xvfb()
    try:
        for adaptive in (True, False):
            r = measure(display, adaptive)
            print(f"adaptive {'on ' if adaptive else 'off'}: orbiting {r['moving_ms']:.1f} ms/frame at "
                  f"{r['moving_scale']:.0%} resolution ({r['moving_frames']} frames); idle refinement "
                  f"{r['idle_ms']:.1f} ms per full-resolution sample")
    finally:
        proc.terminate()


if __name__ == "__main__":
    main()
