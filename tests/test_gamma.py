"""The pixel's gamma encoding (shaders/stages/gamma.glsl) on the GPU against x^(1/2.2)."""
import numpy as np

import sdfgl as sg
from sdfgl import shaderlib

SIDE = 512  # SIDE^2 values of x: a uniform grid over [0, 1] and a geometric one towards 0

VERTEX = """#version 330 core
void main() {
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}"""


def encoded_on_gpu(renderer: sg.Renderer, x: np.ndarray) -> np.ndarray:
    """gammaEncode(vec3(x)) for each of SIDE^2 values, float32 from the GPU."""
    fragment = ("#version 330 core\nuniform sampler2D uX;\nout vec4 outValue;\n" + shaderlib.read("stages/gamma")
                + "\nvoid main() { float x = texelFetch(uX, ivec2(gl_FragCoord.xy), 0).r;\n"
                  "    outValue = vec4(gammaEncode(vec3(x, 0.0, 1.0)), 1.0); }\n")

    def draw() -> np.ndarray:
        ctx = renderer.ctx
        prog = ctx.program(vertex_shader=VERTEX, fragment_shader=fragment)
        src = ctx.texture((SIDE, SIDE), 1, x.astype(np.float32).tobytes(), dtype="f4")
        out = ctx.texture((SIDE, SIDE), 4, dtype="f4")
        fbo = ctx.framebuffer(color_attachments=[out])
        vao = ctx.vertex_array(prog, [])
        try:
            src.use(0)
            prog["uX"].value = 0
            fbo.use()
            ctx.viewport = (0, 0, SIDE, SIDE)
            vao.render(vertices=3)
            return np.frombuffer(fbo.read(components=4, dtype="f4"), np.float32).reshape(-1, 4)
        finally:
            for o in (vao, fbo, out, src, prog):
                o.release()
    return renderer.run(draw)


def test_gamma_encoding_is_within_a_twentieth_of_an_8_bit_level(renderer: sg.Renderer) -> None:
    n = SIDE * SIDE
    x = np.concatenate([np.linspace(0.0, 1.0, n // 2), np.geomspace(1e-9, 0.05, n - n // 2)])
    got = encoded_on_gpu(renderer, x)
    exact = x ** (1 / 2.2)
    err = np.abs(got[:, 0].astype(np.float64) - exact)
    assert err.max() * 255 < 0.06, f"largest error {err.max() * 255:.3f} of a level at x = {x[err.argmax()]:.3g}"
    assert got[0, 1] == 0.0 and 255 * abs(got[0, 2] - 1.0) < 0.06  # black stays black, white within the bound
    levels = np.round(got[:, 0] * 255)
    assert np.mean(levels != np.round(exact * 255)) < 0.05  # 8-bit values nearly all as pow() gives them
    assert np.all(np.diff(got[: n // 2, 0]) >= -1e-7)  # monotone over the uniform grid
