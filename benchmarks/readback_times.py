"""How long reading a render back takes at 1920x1080, by output, beside the raw texture read.

    python benchmarks/readback_times.py [repeats]

``render()``'s ``timings["read_s"]`` (every output in the caller's layout: uint8 RGB colour,
float32 depth, normal and int32 steps, row 0 at the top) against ``glGetTexImage`` of the same
textures as they lie (bottom row first, all four channels), which is the floor. Variants are
interleaved; medians are printed.
"""
import statistics
import sys
import time

import sdfgl as sg

SIZE = (1920, 1080)
OUTPUTS = {"color": ("color",), "color + depth + normal + steps": ("color", "depth", "normal", "steps")}


def main(repeats: int = 9) -> None:
    renderer = sg.Renderer()
    scene = sg.sphere(1) | sg.box(1.5).translate((1, 0, 0))
    for outs in OUTPUTS.values():
        renderer.render(scene, size=SIZE, outputs=outs)  # compile and allocate once
    read = {name: [] for name in OUTPUTS}
    raw = {name: [] for name in OUTPUTS}
    for _ in range(repeats):
        for name, outs in OUTPUTS.items():  # interleaved: load drifts hit every variant alike
            res = renderer.render(scene, size=SIZE, outputs=outs)
            read[name].append(res.timings["read_s"])
            targets = renderer.targets.get(renderer.ctx, SIZE, res.settings.outputs)

            def tex_read() -> float:
                t0 = time.perf_counter()
                for tex in targets.textures.values():
                    tex.read()
                return time.perf_counter() - t0
            raw[name].append(renderer.run(tex_read))
    print(f"| outputs at {SIZE[0]}x{SIZE[1]} | render() read-back ms (median) | glGetTexImage ms (median) |")
    print("|---|---|---|")
    for name in OUTPUTS:
        print(f"| {name} | {statistics.median(read[name]) * 1000:.1f} | {statistics.median(raw[name]) * 1000:.1f} |")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 9)
