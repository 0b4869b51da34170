"""What llvmpipe skips: the body of an ``if`` whose condition no pixel takes, against a loop
that no pixel enters (the reason sdfgl.compiler.guards tests only children that loop).

A full-screen 1280x720 draw whose fragment shader runs 300 dependent sin/cos operations
inside ``if (cond)`` or ``for (k < cond)``, the condition a uniform (0 or 1) or half the
8-pixel tiles of a texture; median of 5 draws each, finish() included.

    python benchmarks/llvmpipe_branches.py
"""
import time

import moderngl
import numpy as np

VS = ("#version 330\nvoid main() { gl_Position = vec4(gl_VertexID == 1 ? 3.0 : -1.0, "
      "gl_VertexID == 2 ? 3.0 : -1.0, 0.0, 1.0); }")
BODY = "\n".join(f"        x = sin(x * 1.0001 + {i}.0) * cos(x + {i}.5);" for i in range(300))


def shader(cond: str, form: str) -> str:
    head = "if ((g & 1u) != 0u) {" if form == "if" else "for (int k = 0; k < int(g & 1u); k++) {"
    return f"""#version 330
out vec4 c;
uniform uint u;
uniform sampler2D tiles;
void main() {{
    float x = gl_FragCoord.x * 0.001;
    uint g = {cond};
    {head}
{BODY}
    }}
    c = vec4(x);
}}"""


def main() -> None:
    ctx = moderngl.create_context(standalone=True, backend="egl")
    size, tile = (1280, 720), 8
    fbo = ctx.simple_framebuffer(size)
    fbo.use()
    half = np.ones((size[1] // tile, size[0] // tile), np.float32)
    half[:, ::2] = 0.0
    tex = ctx.texture(half.shape[::-1], 1, half.tobytes(), dtype="f4")
    tex.use(0)
    print(f"GL: {ctx.info['GL_RENDERER']}, {size[0]}x{size[1]}")
    cases = [("uniform 0", "u", 0), ("uniform 1", "u", 1),
             ("half the tiles", "uint(texelFetch(tiles, ivec2(gl_FragCoord.xy) / 8, 0).r)", 1)]
    for form in ("if", "for"):
        for name, cond, value in cases:
            prog = ctx.program(vertex_shader=VS, fragment_shader=shader(cond, form))
            if "u" in prog:
                prog["u"].value = value
            if "tiles" in prog:
                prog["tiles"].value = 0
            vao = ctx.vertex_array(prog, [])
            vao.render(vertices=3)
            ctx.finish()
            times = []
            for _ in range(5):
                t = time.perf_counter()
                vao.render(vertices=3)
                ctx.finish()
                times.append(time.perf_counter() - t)
            print(f"{form:>3}, condition {name:<15} {1000 * np.median(times):7.1f} ms")
            vao.release()
            prog.release()


if __name__ == "__main__":
    main()
