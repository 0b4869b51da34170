"""Combiners: hard, quadratic, circular and chamfer unions; colours blend across smooth seams.
The blend radius is live: a slider in `sdfgl view` (panel) and `sdfgl html`."""
import sdfgl as sg

k = sg.param(0.35, "blend radius", range=(0.05, 0.6))


def pair(**kw):
    return sg.union(sg.box(0.8).color(0.85, 0.3, 0.2), sg.sphere(0.5).translate((0.45, 0.35, 0)).color(0.2, 0.5, 0.9),
                    **kw)


scene = sg.union(pair().translate((-2.7, 0.4, 0)), pair(k=k).translate((-0.9, 0.4, 0)),
                 pair(k=k, blend="circular").translate((0.9, 0.4, 0)),
                 pair(k=k, blend="chamfer").translate((2.7, 0.4, 0)))
camera = sg.OrbitCamera(target=(0, 0.4, 0), distance=6.5, yaw=10, pitch=25)
settings = {"ground": True}
