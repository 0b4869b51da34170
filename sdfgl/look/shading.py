"""GLSL of the look: the shadow functions the lights use, each light's code, ambient
light and the background. Only lights that exist have code, and only the shadow kinds
they cast are included (each shadow file with its function renamed, so a hard-shadowed
and a soft-shadowed light can share one shader)."""
from __future__ import annotations

from typing import Any, Callable

from .. import shaderlib
from .background import Background
from .lights import DEFAULT_AMBIENT, DEFAULT_LIGHTS, Light

SHADOW_FUNCTIONS = {"hard": "shadowHard", "soft": "shadowSoft", "march": "shadowMarch"}

Fmt = Callable[[float], str]


def _vec3(c: Any, f: Fmt) -> str:
    return f"vec3({', '.join(f(x) for x in c)})"


def shadow_kinds(lights: tuple[Light, ...], setting: Any, implicit: bool) -> list[str]:
    """The shadow kinds (in SHADOW_FUNCTIONS) the lights cast, in a stable order."""
    kinds = []
    for lt in lights:
        k = lt.shadow_kind(setting)
        if k:
            k = "march" if implicit else k
            if k not in kinds:
                kinds.append(k)
    return sorted(kinds)


def _light_block(i: int, lt: Light, kind: Any, f: Fmt, at: str | None = None) -> str:
    rad = _vec3(lt.radiance(), f)
    if lt.kind == "directional":
        head = f"        vec3 L = {_vec3(lt.vector, f)};\n        float atten = 1.0;\n        float tmax = 1e30;\n"
    else:
        fall = "1.0" if lt.range is None else f"1.0 / (1.0 + dist * dist * {f(1.0 / lt.range ** 2)})"
        head = (f"        vec3 toLight = {at or _vec3(lt.vector, f)} - pos;\n"
                f"        float dist = max(length(toLight), 1e-20);\n"
                f"        vec3 L = toLight / dist;\n        float atten = {fall};\n        float tmax = dist;\n")
    if kind:
        vis = f"dif > 0.0 ? {SHADOW_FUNCTIONS[kind]}Visibility(pos, nor, t, L, tmax) : 0.0"
    else:
        vis = "occ" if lt.fill else "1.0"
    body = (f"    {{  // light {i}: {lt.kind}{', fill' if lt.fill else ''}, shadow {kind or 'none'}\n{head}"
            f"        float dif = clamp(dot(nor, L), 0.0, 1.0);\n"
            f"        float vis = {vis};\n"
            f"        vec3 c = {rad} * (atten * dif * vis);\n"
            f"        diffuse += c;\n")
    if not lt.fill:
        body += "        highlight += c * pow(clamp(dot(nor, normalize(L - rd)), 0.0, 1.0), s.shininess);\n"
    return body + "    }\n"


def shade_function(lights: tuple[Light, ...] | None, ambient: Any, setting: Any, implicit: bool, f: Fmt,
                   metals: bool = False, positions: dict[int, str] | None = None) -> str:
    """GLSL of ``vec3 shadeSurface(pos, nor, rd, Surface s, t)`` for these lights; with
    ``metals`` (some node sets surface fields), metallic surfaces reflect the background
    along the mirror direction in place of the ambient light. ``positions``: GLSL of point
    light i's position relative to the shader origin (default: its world position)."""
    rig = DEFAULT_LIGHTS if lights is None else lights
    sky, ground = DEFAULT_AMBIENT if ambient is None else ambient
    out = ["vec3 shadeSurface(vec3 pos, vec3 nor, vec3 rd, Surface s, float t) {",
           "    float occ = occlusion(pos, nor);",
           "    vec3 diffuse = vec3(0.0);",
           "    vec3 highlight = vec3(0.0);",
           "    vec3 ambient = vec3(0.0);"]
    for i, lt in enumerate(rig):
        k = lt.shadow_kind(setting)
        at = (positions or {}).get(i)
        out.append(_light_block(i, lt, ("march" if implicit else k) if k else False, f, at).rstrip("\n"))
    if any(sky):
        out.append(f"    ambient += {_vec3(sky, f)} * ((0.5 + 0.5 * nor.y) * occ);")
    if any(ground):
        out.append(f"    ambient += {_vec3(ground, f)} * ((0.5 - 0.5 * nor.y) * occ);")
    if metals:
        out.append("    ambient = mix(ambient, background(reflect(rd, nor)) * occ, s.metallic);")
    out += ["    return combineLight(s, diffuse, ambient, highlight);", "}"]
    return "\n".join(out)


def shadow_code(kinds: list[str]) -> list[tuple[str, str]]:
    """(code, owner) of the shadow functions and their light-visibility wrappers."""
    files = {"hard": "stages/shadow_hard", "soft": "stages/shadow_soft", "march": "stages/shadow_march"}
    out = []
    for k in kinds:
        fn = SHADOW_FUNCTIONS[k]
        out.append((f"#define shadow {fn}", "(look)"))
        out.append((shaderlib.read(files[k]), f"shaders/{files[k]}.glsl"))
        out.append(("#undef shadow", "(look)"))
        out.append((shaderlib.read("templates/light_visibility").replace("SHADOWFN", fn), "shaders/templates/light_visibility.glsl"))
    return out


def background_code(bg: Background, f: Fmt) -> tuple[str, str]:
    """(code, owner) of ``vec3 background(vec3 rd)``."""
    if bg.kind == "sky":
        return shaderlib.read("stages/background_sky"), "shaders/stages/background_sky.glsl"
    if bg.kind == "color":
        return f"vec3 background(vec3 rd) {{\n    return {_vec3(bg.colors[0], f)};\n}}", "(look: background)"
    top, bottom = (_vec3(c, f) for c in bg.colors)
    return (f"// top of the image to bottom\nvec3 background(vec3 rd) {{\n"
            f"    return mix({bottom}, {top}, clamp(gl_FragCoord.y / uResolution.y, 0.0, 1.0));\n}}",
            "(look: background)")


def unshadowed_tile_function(lights: tuple[Light, ...] | None, setting: Any, f: Fmt) -> str:
    """GLSL of ``bool tileUnshadowed(vec3 c, float r)`` for the coarse pass: whether no shadow
    ray from a point within ``r`` of ``c`` toward a shadowed light can enter the scene box (then
    each such point's visibility is 1 without a march). A ray along L from such a point misses
    the box when the ray from ``c`` misses the box grown by ``r``. False where a shadowed light
    is a point light (its direction varies over the tile)."""
    rig = DEFAULT_LIGHTS if lights is None else lights
    out = ["bool tileUnshadowed(vec3 c, float r) {",
           "    vec3 lo = BOUNDS_LO - vec3(r), hi = BOUNDS_HI + vec3(r);"]
    for lt in rig:
        if not lt.shadow_kind(setting):
            continue
        if lt.kind != "directional":
            return "bool tileUnshadowed(vec3 c, float r) {\n    return false;  // a shadowed point light\n}"
        out += [f"    {{  // the ray from c toward {_vec3(lt.vector, f)}, against the grown box",
                f"        vec3 L = {_vec3(lt.vector, f)};",
                "        vec3 inv = 1.0 / (L + vec3(equal(L, vec3(0.0))) * 1e-30);",
                "        vec3 t0 = (lo - c) * inv, t1 = (hi - c) * inv;",
                "        vec3 tn = min(t0, t1), tf = max(t0, t1);",
                "        if (max(max(tn.x, tn.y), max(tn.z, 0.0)) <= min(min(tf.x, tf.y), tf.z)) return false;",
                "    }"]
    out += ["    return true;", "}"]
    return "\n".join(out)
