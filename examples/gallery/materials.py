"""Lights and materials: gold, brushed steel, glossy plastic and a glowing core under a
warm soft-shadowed key light, a cool rim light and an orange point light."""
import sdfgl as sg

scene = sg.union(
    sg.sphere(0.6).material("gold", metallic=1.0, roughness=0.35).translate((-1.5, 0.6, 0)),
    sg.rounded_box(1.0, 0.15).material("#b0b4b8", metallic=0.8, roughness=0.6).translate((0, 0.5, 0)),
    sg.torus(0.45, 0.15).material("crimson", specular=0.9, shininess=180).rotate(60, sg.X).translate((1.5, 0.6, 0)),
    sg.union(sg.sphere(0.25).material((20, 20, 20), emission="#ffaa33"),
             sg.sphere(0.35).translate((0.35, 0, 0)).material("teal", roughness=0.2), k=0.2).translate((-0.3, 1.25, 0.8)),
)
camera = sg.OrbitCamera(target=(0, 0.6, 0), distance=5.2, yaw=15, pitch=22)
settings = {
    "ground": True,
    "lights": [sg.directional_light((0.5, 0.8, 0.4), "#fff1dc", 1.0, shadow="soft"),
               sg.directional_light((-0.6, 0.3, -0.8), "#8fb4ff", 0.6, shadow=False),
               sg.point_light((0.0, 1.6, 1.6), "orange", 1.2, range=1.5, shadow="hard")],
    "ambient": ("#3a4660", "#2a2420"),
}
