"""A branching tree by mirror recursion: 4^6 branches, cost linear in the six levels."""
import sdfgl as sg

scene = sg.tree(6, 1.0, 0.07, 32, 0.68).color(0.45, 0.35, 0.25)
camera = sg.OrbitCamera(target=(0, 1.6, 0), distance=6.5, yaw=20, pitch=12)
settings = {"ground": True}
