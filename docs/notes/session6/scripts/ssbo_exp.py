import time, statistics, numpy as np, moderngl
import sdfgl as sg
from sdfgl.bench_big import growth, NO_SHADING
from sdfgl.codegen import generate
from sdfgl.settings import Settings
from sdfgl.render import shader_origin, camera_uniforms, scene_uniforms, _set_uniform
from sdfgl import shaderlib
from sdfgl.gl.dialect import of_source
ctx = moderngl.create_context(standalone=True, backend="egl", require=430)
size=(320,240)
fbo = ctx.simple_framebuffer(size)
vert330 = shaderlib.read("fullscreen.vert")
def prog_of(text, ver="330"):
    v = vert330.replace("#version 330 core", f"#version {ver} core")
    return ctx.program(vertex_shader=v, fragment_shader=text)
TEX = """uniform sampler2D uData;

vec4 dataFetch(int i) {
    return texelFetch(uData, ivec2(i & 1023, i >> 10), 0);
}"""
variants = []
for n in (16, 1024):
    s, c = growth(n, 0)
    st = Settings.build(**NO_SHADING)
    org = shader_origin(s, c.eye)
    src = generate(s, st, org)
    variants.append((f"{n} tex", s, c, org, src, src.text, None))
    if src.data:
        arr = np.ascontiguousarray(src.data[0][1], dtype=np.float32).reshape(-1, 4)
        assert TEX in src.text
        t_ssbo = src.text.replace("#version 330 core", "#version 430 core").replace(TEX, "layout(std430, binding = 0) readonly buffer DataBuf { vec4 dataBuf[]; };\nvec4 dataFetch(int i) { return dataBuf[i]; }")
        variants.append((f"{n} ssbo", s, c, org, src, t_ssbo, arr))
        t_tbo = src.text.replace(TEX, "uniform samplerBuffer uDataB;\nvec4 dataFetch(int i) { return texelFetch(uDataB, i); }")
        variants.append((f"{n} tbo", s, c, org, src, t_tbo, arr))
progs = []
for name, s, c, org, src, text, arr in variants:
    ver = "430" if "430" in text.split("\n")[0] else "330"
    p = prog_of(text, ver)
    vao = ctx.vertex_array(p, [])
    buf = None
    if arr is not None:
        buf = ctx.buffer(arr.tobytes())
    progs.append((name, p, vao, s, c, org, src, buf, text))
from sdfgl.gl.data import DataTextures
from sdfgl.gl.cache import default_budget
data = DataTextures(default_budget)
import ctypes

import os
from OpenGL import GL
def draw(entry):
    name, p, vao, s, c, org, src, buf, text = entry
    camera_uniforms(p, c, size, org)
    if "uData;" in text:
        scene_uniforms(p, src, s, org, data)
    else:
        for i, prm in enumerate(src.params): pass
    if "dataBuf" in text:
        buf.bind_to_storage_buffer(0)
    if "uDataB" in text:
        tex = entry_tbo[name]
        GL.glActiveTexture(GL.GL_TEXTURE0 + 5)
        GL.glBindTexture(GL.GL_TEXTURE_BUFFER, tex)
        p["uDataB"].value = 5
    fbo.use(); ctx.viewport = (0, 0, *size)
    t0 = time.perf_counter(); vao.render(moderngl.TRIANGLES, vertices=3); ctx.finish()
    return time.perf_counter() - t0
entry_tbo = {}
for e in progs:
    if "tbo" in e[0]:
        tid = GL.glGenTextures(1)
        GL.glBindTexture(GL.GL_TEXTURE_BUFFER, tid)
        GL.glTexBuffer(GL.GL_TEXTURE_BUFFER, GL.GL_RGBA32F, e[7].glo)
        entry_tbo[e[0]] = tid
imgs = {}
times = {e[0]: [] for e in progs}
for rnd in range(9):
    for e in progs:
        dt = draw(e)
        if rnd >= 2: times[e[0]].append(dt)
        if rnd == 0: imgs[e[0]] = np.frombuffer(fbo.read(), np.uint8).copy()
b16 = statistics.median(times["16 tex"])
for k, v in times.items():
    print(k, f"{1000*statistics.median(v):.2f} ms ratio {statistics.median(v)/b16:.2f}")
print("ssbo same image", np.array_equal(imgs["1024 tex"], imgs["1024 ssbo"]), "tbo same", np.array_equal(imgs["1024 tex"], imgs["1024 tbo"]))
