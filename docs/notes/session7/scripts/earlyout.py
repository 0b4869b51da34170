"""1000 robot copies against 1000 spheres, frames interleaved, with source rewrites of the robot loop:
skip (box distance >= best), max (max(f, box distance)), bvif<th> (box distance when farther than th),
sphere (the robot replaced by a sphere), parts (free way by four part boxes), inv (1/d hoisted),
maxdd (free way max(box entry, distance)), exact (the parts' own entries: body and arms boxes,
the head's sphere, the legs' capped cylinders). Usage: earlyout.py KIND ..."""
import dataclasses, sys
from sdfgl.bench import FrameTimer, Progress, Variant, time_interleaved
from sdfgl.bench_big import instances, spheres_like, NO_SHADING
from sdfgl.render import Renderer
BOX = "vec3(-0.349999994, -0.5, -0.180000007), vec3(0.349999994, 0.560000002, 0.180000007)"
HELPER = ("float sdBoxLH(vec3 q, vec3 lo, vec3 hi) { vec3 w = abs(q - 0.5 * (lo + hi)) - 0.5 * (hi - lo); "
          "return length(max(w, 0.0)) + min(max(w.x, max(w.y, w.z)), 0.0); }\n")
OLD = "        float dd = d0_difference(q);\n        best = min(best, dd);\n"
def rewrite(kind):
    def f(src):
        t = src.text
        assert OLD in t
        t = t.replace("float g0Dist(vec3 p) {", HELPER + "float g0Dist(vec3 p) {")
        if kind.startswith("bvif"):
            th = kind[4:]
            new = f"        float g = sdBoxLH(q, {BOX});\n        if (g < {th}) g = max(d0_difference(q), g);\n        best = min(best, g);\n"
            return dataclasses.replace(src, text=t.replace(OLD, new, 1))
        if kind in ("inv", "partsinv"):
            t = t.replace("float g0RayBox(vec3 q, vec3 d, vec3 lo, vec3 hi) {\n    vec3 inv = 1.0 / (d + vec3(equal(d, vec3(0.0))) * 1e-30);",
                          "vec3 gInv;\nfloat g0RayBox(vec3 q, vec3 d, vec3 lo, vec3 hi) {\n    vec3 inv = gInv;")
            assert "vec3 gInv" in t
            t = t.replace("    float free = g0Exit(p, gRayDir, cellLo);", "    float free = g0Exit(p, gRayDir, cellLo);\n    gInv = 1.0 / (gRayDir + vec3(equal(gRayDir, vec3(0.0))) * 1e-30);")
            if kind == "inv":
                return dataclasses.replace(src, text=t)
        if kind == "maxdd":
            oldf = f"free = min(free, g0RayBox(q, gRayDir, {BOX}));"
            assert oldf in t
            return dataclasses.replace(src, text=t.replace(oldf, f"free = min(free, max(dd, g0RayBox(q, gRayDir, {BOX})));"))
        if kind == "skiploop":  # the robot only where its box is nearer than the best; a loop of 0 or 1
            # rounds is a real branch on llvmpipe (an if only masks lanes)
            new = (f"        float bd = sdBoxLH(q, {BOX});\n"
                   "        for (int z = uZero; z < (bd < best ? 1 : 0); z++) best = min(best, d0_difference(q));\n")
            return dataclasses.replace(src, text=t.replace(OLD, new, 1))
        if kind == "exact":
            oldf = f"free = min(free, g0RayBox(q, gRayDir, {BOX}));"
            assert oldf in t
            helper = (
                "float rayCylY(vec3 o, vec3 d, float r, float h) {\n"
                "    float a = d.x * d.x + d.z * d.z; float b = o.x * d.x + o.z * d.z; float c = o.x * o.x + o.z * o.z - r * r;\n"
                "    float disc = b * b - a * c;\n"
                "    if (disc < 0.0 || a < 1e-12) return 3.0e38;\n"
                "    float sq = sqrt(disc); float t0 = (-b - sq) / a; float t1 = (-b + sq) / a;\n"
                "    float iy = 1.0 / (abs(d.y) < 1e-20 ? 1e-20 : d.y);\n"
                "    float y0 = (-h - o.y) * iy; float y1 = (h - o.y) * iy;\n"
                "    float enter = max(max(t0, min(y0, y1)), 0.0); float leave = min(t1, max(y0, y1));\n"
                "    return leave < enter ? 3.0e38 : enter;\n}\n")
            t = t.replace("float g0Dist(vec3 p) {", helper + "float g0Dist(vec3 p) {")
            newf = ("free = min(free, min(min(g0RayBox(q, gRayDir, vec3(-0.2, -0.25, -0.15), vec3(0.2, 0.25, 0.15)), "
                    "g0RayBall(q - vec3(0.0, 0.38, 0.0), gRayDir, 0.18)), min(g0RayBox(q, gRayDir, vec3(-0.35, 0.1, -0.05), "
                    "vec3(0.35, 0.2, 0.05)), min(rayCylY(q - vec3(-0.1, -0.35, 0.0), gRayDir, 0.06, 0.15), "
                    "rayCylY(q - vec3(0.1, -0.35, 0.0), gRayDir, 0.06, 0.15)))));")
            return dataclasses.replace(src, text=t.replace(oldf, newf))
        if kind in ("parts", "partsinv"):
            oldf = f"free = min(free, g0RayBox(q, gRayDir, {BOX}));"
            assert oldf in t
            parts = [((-0.2,-0.25,-0.15),(0.2,0.25,0.15)), ((-0.18,0.2,-0.18),(0.18,0.56,0.18)), ((-0.35,0.1,-0.05),(0.35,0.2,0.05)), ((-0.16,-0.5,-0.06),(0.16,-0.2,0.06))]
            newf = "free = min(free, min(min(" + ", ".join(f"g0RayBox(q, gRayDir, vec3{a}, vec3{b})" for a, b in parts[:2]) + "), min(" + ", ".join(f"g0RayBox(q, gRayDir, vec3{a}, vec3{b})" for a, b in parts[2:]) + ")));"
            return dataclasses.replace(src, text=t.replace(oldf, newf))
        if kind == "sphere":
            new = "        best = min(best, length(q) - 0.35);\n"
        elif kind == "bv":
            new = f"        float bd = sdBoxLH(q, {BOX});\n        best = min(best, bd > 0.1 ? bd : max(d0_difference(q), bd));\n"
        elif kind == "skip":
            new = f"        float bd = sdBoxLH(q, {BOX});\n        if (bd < best) best = min(best, max(d0_difference(q), bd));\n"
        else:
            new = f"        float bd = sdBoxLH(q, {BOX});\n        best = min(best, max(d0_difference(q), bd));\n"
        return dataclasses.replace(src, text=t.replace(OLD, new, 1))
    return f

def main() -> None:
    size = (320, 240)
    r = Renderer(); timer = FrameTimer(r, size)
    n = 1000
    sp = spheres_like(n); ro = instances(n)
    vs = [Variant("spheres", "plain", dict(NO_SHADING), *sp), Variant("robots", "plain", dict(NO_SHADING), *ro)]
    vs += [Variant("robots", k, dict(NO_SHADING), *ro, source=rewrite(k)) for k in sys.argv[1:]]
    time_interleaved(timer, vs, 9, 2, Progress(0, False))
    base = vs[0].result['frame_ms_median']
    for v in vs:
        print(v.scene, v.label, f"{v.result['frame_ms_median']:.1f} ms  ratio {v.result['frame_ms_median']/base:.2f}", flush=True)


if __name__ == "__main__":
    main()
