"""The interactive window (``sdfgl view``, ``sg.show``).

``window`` holds the glfw window and its drawing loop, ``input`` its mouse and keys,
``progressive`` the compiles and frames of the render threads, ``reload`` the scene file's
hot reload and ``state_file`` what the window shows, written for scripts and tests.
"""
from .input import DEBUG_CYCLE, KEYS_HELP, METHOD_CYCLE, MOVE_HOLD_S, SHADOW_CYCLE
from .state_file import ViewState
from .window import Viewer, show

__all__ = ["DEBUG_CYCLE", "KEYS_HELP", "METHOD_CYCLE", "MOVE_HOLD_S", "SHADOW_CYCLE", "Viewer", "ViewState", "show"]
