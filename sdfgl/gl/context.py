"""The headless OpenGL context: EGL through Mesa (llvmpipe on a machine without a GPU)."""
from __future__ import annotations

import moderngl

from ..errors import ContextError

_MISSING_HINT = (
    "sdfgl renders headless through EGL. On Debian/Ubuntu install Mesa's EGL driver with\n"
    "    sudo apt-get install -y libegl1 libegl-mesa0 libgl1-mesa-dri\n"
    "(the project's install.sh does this when run as root)."
)

_context: moderngl.Context | None = None


def headless_context() -> moderngl.Context:
    """The shared EGL context (created on first use, GL 3.3 core or newer)."""
    global _context
    if _context is None:
        try:
            ctx = moderngl.create_context(standalone=True, backend="egl", require=330)
        except Exception as exc:  # moderngl/glcontext raise plain Exceptions
            raise ContextError(f"could not create a headless EGL OpenGL context: {exc}\n{_MISSING_HINT}") from exc
        _context = ctx
    return _context


def describe(ctx: moderngl.Context) -> str:
    """One line naming the GL implementation, e.g. 'llvmpipe (LLVM 15.0.6) / OpenGL 4.5'."""
    info = ctx.info
    return f"{info.get('GL_RENDERER', '?')} / {info.get('GL_VERSION', '?')}"
