"""Physically based renders of sdfgl scenes through Mitsuba 3 (the optional extra ``sdfgl[pbr]``).

    import sdfgl as sg
    img = sg.render_pbr(scene, camera=cam, size=(640, 480), spp=64)   # PBRImage: .hdr, .alpha, .save()
    d = sg.to_mitsuba(scene, camera=cam)                               # a Mitsuba scene dict
    sg.pbr.Material(color=(0.9, 0.6, 0.2), metallic=1, roughness=0.3)  # surface terms
    sg.pbr.Blend(rock, snow, boundary=sg.plane(), width=0.05)          # two materials across a field

The field reaches Mitsuba as an ``sdfgrid`` sampled by the same generated ``map()``
that renders in real time; Mitsuba itself is imported only when a render is asked for.
"""
from .image import PBRImage
from .lighting import Sky, Sun
from .materials import Blend, Material, SceneMaterial
from .render import render_pbr, to_mitsuba

__all__ = ["render_pbr", "to_mitsuba", "PBRImage", "Material", "Blend", "SceneMaterial", "Sky", "Sun"]
