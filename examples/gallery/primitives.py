"""Every primitive family, CSG and a smooth blend: the built-in demo scene."""
from sdfgl.demo import demo_camera, demo_scene

scene = demo_scene()
camera = demo_camera()
settings = {"ground": True}
