"""Trace demo pixels (400x300) with t10a's float64 emulator of march_relaxed:
    PYTHONPATH=<tree> python emudemo.py X,Y ...   (prints every sample and the call kinds)"""
import sys, os, numpy as np
sys.path.insert(0,'/work/notes/s4/t10a_scripts')
from emu import Emu
Emu.NSCAN=3; Emu.DIP=0.7; Emu.MAXS=256
from sdfgl.demo import demo_camera, demo_scene
from sdfgl.reference import trace, _clip
scene, cam = demo_scene(), demo_camera()
W,H=400,300
o,d=cam.rays(W,H); o=o.reshape(-1,3); d=d.reshape(-1,3)
tmin,tmax=_clip(scene,o,d,1000.0)
pa=cam.pixel_angle(H)
for p in sys.argv[1:]:
    x,y=map(int,p.split(',')); k=y*W+x
    em=Emu(scene,pa,log=True)
    t=em.march(o[k],d[k],tmin[k],tmax[k]); print(x,y,"emu t",t,"steps",em.steps,"iters",em.it,"calls",em.tags)
