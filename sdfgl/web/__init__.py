"""Scenes in the browser: one-file HTML views, the notebook widget and inline previews.

    sg.save_html(scene, "part.html")     # WebGL2 page, no network needed
    w = sg.widget(scene, size=(640, 400)) # Jupyter view synced with Python (needs sdfgl[web])

The browser runs the shader that :func:`sdfgl.compiler.generate` writes for the "webgl2"
dialect: the same .glsl files and map() as the desktop render.
"""
from .html import save_html, to_html

__all__ = ["save_html", "to_html"]
