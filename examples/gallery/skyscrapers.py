"""Skyscrapers (after Monzón González's Zaragoza thesis): mirror symmetry multiplies the columns, finite repetition
stacks the floors, a glass core, and a mirror copies the whole building."""
import sdfgl as sg

column = sg.box((0.2, 4.0, 0.2)).translate((0.7, 2.0, 0.7)).symmetric("xz")
floors = sg.box((1.7, 0.08, 1.7)).repeat((0, 0.5, 0), count=(0, 3, 0)).translate((0, 2.0, 0))
core = sg.box((1.3, 4.0, 1.3)).translate((0, 2.0, 0)).color(0.35, 0.5, 0.65)
building = sg.union(column.color(0.75, 0.74, 0.7), floors.color(0.75, 0.74, 0.7), core)
scene = building.translate((1.4, 0, 0)).mirror(sg.X)
camera = sg.OrbitCamera(target=(0, 2.0, 0), distance=11, yaw=30, pitch=18)
settings = {"ground": True}
