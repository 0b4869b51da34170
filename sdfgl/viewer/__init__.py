"""The interactive window (``sdfgl view``, ``sg.show``).

``window`` holds the glfw window, its input and drawing loop.
"""
from .window import (DEBUG_CYCLE, KEYS_HELP, METHOD_CYCLE, MOVE_HOLD_S, SHADOW_CYCLE, Viewer, ViewState,
                     show)

__all__ = ["DEBUG_CYCLE", "KEYS_HELP", "METHOD_CYCLE", "MOVE_HOLD_S", "SHADOW_CYCLE", "Viewer", "ViewState", "show"]
