"""Steps image of the demo (`sdfgl render --demo` settings) for blockmax.py: python demo_steps.py WxH out.npz"""
import sys, numpy as np
from sdfgl.demo import demo_camera, demo_scene
from sdfgl.render import render
W, H = map(int, sys.argv[1].split("x"))
res = render(demo_scene(), demo_camera(), (W, H), outputs=("color", "steps"), shadows="soft", ao=True, ground=True)
np.savez_compressed(sys.argv[2], **{"demo.steps": res.steps.astype(np.int32)})
