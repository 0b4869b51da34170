"""Text: a plate with a name engraved into it and a raised, rounded line of text above."""
import sdfgl as sg

plate = sg.rounded_box((2.4, 0.9, 0.16), 0.04).color(0.35, 0.45, 0.6)
engraved = plate - sg.extrude(sg.text("sdfgl", size=0.55, align="center"), 0.1).translate((0, -0.2, 0.08))
raised = sg.extrude(sg.text("Hello, wörld!", size=0.3, align="center").round(0.01), 0.12)
scene = engraved | raised.color(0.9, 0.6, 0.2).translate((0, 0.65, 0))
camera = sg.OrbitCamera(target=(0, 0.3, 0), distance=3.0, yaw=15, pitch=15)
