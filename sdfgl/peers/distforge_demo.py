"""The sdfgl demo scene built with DistForge, timed through its ``save_frames`` or
``save_frame`` (DistForge draws in a glfw window, so this needs an X display).

    DISPLAY=:99 python -m sdfgl.peers.distforge_demo OUT.mp4 FRAMES WIDTH HEIGHT
    DISPLAY=:99 python -m sdfgl.peers.distforge_demo OUT.png 1 WIDTH HEIGHT

Prints one JSON line: {"frames", "seconds", "fps"}; "seconds" is the time of the save call
alone. Run in a subprocess by benchmarks/animate_figures.py and by ``sdfgl bench``'s PNG
rows (sdfgl.bench_png), under Xvfb; an interpreter without DistForge fails at the import.
"""
import json
import math
import sys
import time


def demo_scene():
    """The parts of sdfgl.demo.demo_scene with DistForge's primitives (the same sizes and places)."""
    import distforge as df
    drill = df.cylinder(0.5, 4).rotate(df.Z, math.pi / 2).union(df.cylinder(0.5, 4),
                                                                df.cylinder(0.5, 4).rotate(df.X, math.pi / 2))
    csg = df.sphere(1).intersection(df.box(1.5)).color(0.85, 0.3, 0.2).difference(drill)
    blob = df.sphere(0.45).translate((-0.25, 0, 0)).union(df.sphere(0.35).translate((0.3, 0.15, 0)),
                                                         blend=0.3).color(0.3, 0.6, 0.9)
    parts = [
        csg.translate((0, 0.75, 0)),
        df.torus(0.5, 0.15).color(0.9, 0.75, 0.2).rotate(df.X, math.radians(20)).translate((2.2, 0.65, 0)),
        df.line((-0.4, 0, 0), (0.4, 0.5, 0), 0.2).color(0.4, 0.8, 0.4).translate((-2.2, 0.2, 0)),
        df.box(0.8).round(0.15).color(0.6, 0.4, 0.8).translate((0, 0.4, -2.2)),
        df.cone(1.0, 0.45, 0.1).color(0.9, 0.5, 0.2).translate((2.0, 0.5, -1.8)),
        df.ellipsoid((0.6, 0.3, 0.4)).color(0.8, 0.8, 0.85).translate((-2.0, 0.3, -1.8)),
        df.octahedron(0.5).color(0.2, 0.7, 0.7).translate((2.0, 0.5, 1.9)),
        df.hex_prism(0.4, 0.8).color(0.75, 0.3, 0.5).rotate(df.X, math.pi / 2).translate((-2.0, 0.4, 1.9)),
        blob.translate((0, 0.45, 2.1)),
    ]
    scene = parts[0].union(*parts[1:])
    return scene.union(df.plane((0, 1, 0), (0, -0.3, 0)).color(0.7, 0.7, 0.7))


def main() -> None:
    import distforge as df
    out, frames, w, h = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
    scene = demo_scene()
    cam = df.Camera(position=(4.5, 3.5, 5.4), target=(0, 0.4, 0), zoom=2.2)  # about the framing of sdfgl.demo.demo_camera
    t0 = time.perf_counter()
    if out.endswith(".png") and frames == 1:
        scene.save_frame(out, camera=cam, width=w, height=h)
    else:
        scene.save_frames(out, camera=cam, frames=frames, fps=30, stitch_video=out.endswith((".mp4", ".gif")),
                          width=w, height=h)
    s = time.perf_counter() - t0
    print(json.dumps({"frames": frames, "seconds": s, "fps": frames / s}))


if __name__ == "__main__":
    main()
