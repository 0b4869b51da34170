"""The pixel's gamma encoding (shaders/stages/gamma.glsl) against pow(x, 1/2.2) at 1280x720.

    python benchmarks/gamma_encode.py [repeats]

Two full-view programs that differ only in the encoding draw the sky's gradient (the work of a
pixel that no surface covers); the draws are interleaved and timed with ctx.finish() and a wall
clock; medians are printed (tests/test_gamma.py holds the encoding's error).
"""
import statistics
import sys
import time

import sdfgl as sg
from sdfgl import shaderlib

SIZE = (1280, 720)
VERTEX = """#version 330 core
void main() {
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}"""
SKY = """uniform vec2 uSize;
out vec4 outColor;
vec3 sky() {
    vec3 rd = normalize(vec3((2.0 * gl_FragCoord.xy - uSize) / uSize.y, -1.5));
    float h = clamp(rd.y, -1.0, 1.0);
    return h >= 0.0 ? mix(vec3(0.86, 0.88, 0.91), vec3(0.38, 0.56, 0.84), sqrt(h))
                    : mix(vec3(0.86, 0.88, 0.91), vec3(0.55, 0.54, 0.52), sqrt(-h));
}
"""
ENCODINGS = {"pow(x, 1/2.2)": "outColor = vec4(pow(clamp(sky(), 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);",
             "gammaEncode": "outColor = vec4(gammaEncode(sky()), 1.0);"}


def main(repeats: int = 15) -> None:
    renderer = sg.Renderer()

    def run() -> dict[str, list[float]]:
        ctx = renderer.ctx
        fbo = ctx.simple_framebuffer(SIZE)
        vaos = {}
        for name, body in ENCODINGS.items():
            prog = ctx.program(vertex_shader=VERTEX, fragment_shader="#version 330 core\n" + SKY
                               + shaderlib.read("stages/gamma") + "\nvoid main() { " + body + " }\n")
            prog["uSize"].value = SIZE
            vaos[name] = ctx.vertex_array(prog, [])
        fbo.use()
        times: dict[str, list[float]] = {name: [] for name in ENCODINGS}
        for r in range(repeats + 2):
            for name, vao in vaos.items():  # interleaved
                t0 = time.perf_counter()
                vao.render(vertices=3)
                ctx.finish()
                if r >= 2:  # two warm-up rounds (llvmpipe builds its code at the first draw)
                    times[name].append(time.perf_counter() - t0)
        return times
    times = renderer.run(run)
    print(f"| encoding at {SIZE[0]}x{SIZE[1]} | frame ms (median of {repeats}) |")
    print("|---|---|")
    for name, ts in times.items():
        print(f"| {name} | {1000 * statistics.median(ts):.2f} |")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 15)
