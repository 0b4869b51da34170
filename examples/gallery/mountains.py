"""Noise mountains (after Monzón González's Zaragoza thesis) with a water plane: terrain marched with 5 octaves
and shaded with 10, water flat but shaded with 6 octaves of ripples."""
import sdfgl as sg

terrain = sg.plane().displace(1.2, 0.25, 5, normal_octaves=10).color(0.55, 0.5, 0.45)
water = sg.plane((0, 1, 0), (0, -0.2, 0)).displace(0.04, 2.0, 0, normal_octaves=6).color(0.2, 0.4, 0.6)
scene = sg.union(terrain, water)
camera = sg.Camera.look_at((0, 3, 9), (0, 0, 0), fov=50)
settings = {"max_dist": 60.0}
