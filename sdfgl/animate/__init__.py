"""Animation and batch rendering: the clock, keyframes, camera paths, frame writers, batch jobs.

    t = sg.time()
    scene = sg.sphere(1 + 0.2 * sg.sin(t))
    sg.animate(scene, "spin.mp4", seconds=4, fps=30, camera=sg.turntable(distance=5, pitch=20))

Batch jobs (``sdfgl batch jobs.json``) live in :mod:`sdfgl.animate.batch`.
"""
from .animation import AnimationResult, animate
from .keyframes import keyframes
from .paths import CameraPath, LookAtPath, Turntable, camera_path, turntable
from .writers import FrameWriter, GifWriter, PngSequenceWriter, VideoWriter, open_writer

__all__ = ["animate", "AnimationResult", "keyframes", "turntable", "camera_path", "CameraPath", "Turntable",
           "LookAtPath", "FrameWriter", "GifWriter", "PngSequenceWriter", "VideoWriter", "open_writer"]
