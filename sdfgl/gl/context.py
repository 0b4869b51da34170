"""Where GL runs: one thread that owns the headless EGL context, safe across threads and fork.

The threading model
-------------------
An OpenGL context is current on at most one thread, and a GL call made on a thread where
it is not current silently does nothing (or draws garbage). So sdfgl never moves its
headless context between threads: one daemon thread, ``sdfgl-gl``, creates the EGL
context and makes every GL call on it. ``render()``, ``evaluate()``, ``Renderer``'s program
cache and every other GL user hand their GL work to that thread through a queue
(:meth:`GLThread.call`) and wait for the result, so any thread may call them at any time;
concurrent callers are served one at a time, in arrival order. Scene code generation
stays on the calling thread. Every GL object (programs, textures, framebuffers) lives on
the GL thread and is only touched there.

A ``Renderer`` built on a context someone else made current (the viewer's window) runs its
GL work inline on the calling thread instead (:class:`CurrentContext`): use it from the
thread that owns that window.

Fork
----
After ``fork()`` only the forking thread exists in the child, and Mesa's llvmpipe
rasterizer threads, which belong to the EGL display, are gone: any GL call in the child,
even on a brand-new context of the inherited display, waits forever for them. So an
at-fork handler (``os.register_at_fork``) tears the headless EGL state down *before* the
fork (it waits for the GL work in flight, destroys the context and terminates the EGL
display), and both processes create a fresh context on their next render. The cost is
that the parent recompiles its programs after a fork. A child never touches its parent's
context. A process forked behind Python's back (no at-fork handlers ran) gets a
:class:`~sdfgl.errors.ContextError` instead of a hang.
"""
from __future__ import annotations

import atexit
import ctypes
import os
import queue
import threading
import weakref
from concurrent.futures import Future
from typing import Any, Callable, Iterator, TypeVar

import moderngl

from ..errors import ContextError
from .memory import limit_malloc_arenas

T = TypeVar("T")

_MISSING_HINT = (
    "sdfgl renders headless through EGL. On Debian/Ubuntu install Mesa's EGL driver with\n"
    "    sudo apt-get install -y libegl1 libegl-mesa0 libgl1-mesa-dri\n"
    "(the project's install.sh does this when run as root)."
)


def _egl_names() -> Iterator[str]:
    """Names to load libEGL by; the library search (ctypes.util spawns ldconfig) only if the usual ones fail."""
    yield "libEGL.so.1"
    yield "libEGL.so"
    import ctypes.util
    found = ctypes.util.find_library("EGL")
    if found:
        yield found


def _load_egl() -> Any:
    """libEGL through ctypes (for what glcontext does not expose: releasing and terminating)."""
    for name in _egl_names():
        try:
            lib = ctypes.CDLL(name)
        except OSError:
            continue
        lib.eglGetCurrentDisplay.restype = ctypes.c_void_p
        lib.eglGetCurrentContext.restype = ctypes.c_void_p
        lib.eglMakeCurrent.argtypes = [ctypes.c_void_p] * 4
        lib.eglDestroyContext.argtypes = [ctypes.c_void_p] * 2
        lib.eglTerminate.argtypes = [ctypes.c_void_p]
        return lib
    return None


def _create_egl_context() -> moderngl.Context:
    """A standalone EGL context, naming the usual sonames first: glcontext would otherwise search
    for libGL and libEGL (ctypes.util runs ldconfig) on every context; the search only if those fail."""
    try:
        return moderngl.create_context(standalone=True, backend="egl", require=330, libgl="libGL.so.1",
                                       libegl="libEGL.so.1")
    except Exception:  # moderngl/glcontext raise plain Exceptions
        return moderngl.create_context(standalone=True, backend="egl", require=330)


class GLThread:
    """One daemon thread that owns one headless EGL context and runs every GL call on it."""

    def __init__(self, name: str = "sdfgl-gl") -> None:
        self.name = name
        self.epoch = 0          # bumped whenever the context is replaced: caches of the old one are void
        self._ctx: moderngl.Context | None = None
        self._egl: tuple[int, int] | None = None  # (EGLDisplay, EGLContext) of self._ctx
        self._orphans: list[Any] = []             # wrappers of destroyed contexts: never deallocated in GL
        self._reset()
        _threads.add(self)

    def _reset(self) -> None:
        self.pid = os.getpid()
        self._jobs: queue.SimpleQueue = queue.SimpleQueue()
        self._thread: threading.Thread | None = None
        self._ident: int | None = None
        self._start_lock = threading.Lock()
        self._resume: threading.Event | None = None  # set while the thread is parked across a fork

    # -- running work on the GL thread ------------------------------------------------------
    def call(self, fn: Callable[..., T], *args: Any, **kwargs: Any) -> T:
        """Run ``fn(*args, **kwargs)`` on the GL thread and return its result (or raise its error).

        Called on the GL thread itself (from inside such a call) it runs inline."""
        if threading.get_ident() == self._ident:
            return fn(*args, **kwargs)
        self._check_process()
        fut: Future = Future()
        self._jobs.put((fut, fn, args, kwargs))
        return fut.result()

    def submit(self, fn: Callable[..., Any], *args: Any) -> None:
        """Queue ``fn(*args)`` on the GL thread without waiting (if that thread is running)."""
        if self.pid == os.getpid() and self._thread is not None and self._thread.is_alive():
            self._jobs.put((Future(), fn, args, {}))

    def _check_process(self) -> None:
        if self.pid != os.getpid():  # forked without the at-fork handlers (e.g. a raw fork syscall)
            if self._ctx is not None:
                raise ContextError("this process was forked while sdfgl's GL context was live, without Python's "
                                   "at-fork handlers running; the inherited context cannot be used. Fork with "
                                   "os.fork or multiprocessing, or start the child with the 'spawn' method.")
            self._reset()
        if self._thread is None or not self._thread.is_alive():
            with self._start_lock:
                if self._thread is None or not self._thread.is_alive():
                    ready = threading.Event()
                    self._thread = threading.Thread(target=self._loop, args=(ready,), name=self.name, daemon=True)
                    self._thread.start()
                    ready.wait()

    def _loop(self, ready: threading.Event) -> None:
        self._ident = threading.get_ident()
        ready.set()
        jobs = self._jobs
        while True:
            job = jobs.get()
            fut, fn, args, kwargs = job
            if not fut.set_running_or_notify_cancel():
                continue
            try:
                fut.set_result(fn(*args, **kwargs))
            except BaseException as exc:  # noqa: BLE001 - handed to the caller, who re-raises it
                fut.set_exception(exc)
            del fut, fn, args, kwargs, job

    # -- the context ------------------------------------------------------------------------
    @property
    def ctx(self) -> moderngl.Context:
        """The EGL context (created on first use). Make GL calls on it only through :meth:`call`."""
        ctx = self._ctx
        return ctx if ctx is not None else self.call(self._ensure)

    def _ensure(self) -> moderngl.Context:
        if self._ctx is None:
            limit_malloc_arenas()
            try:
                ctx = _create_egl_context()
            except Exception as exc:  # moderngl/glcontext raise plain Exceptions
                raise ContextError(f"could not create a headless EGL OpenGL context: {exc}\n{_MISSING_HINT}") from exc
            ctx.info  # noqa: B018 - read once here: describe() may then run on any thread
            egl = _EGL
            self._egl = (egl.eglGetCurrentDisplay(), egl.eglGetCurrentContext()) if egl is not None else None
            self._ctx = ctx
            self.epoch += 1
        return self._ctx

    def _teardown(self) -> None:
        """Destroy the context and terminate its EGL display (joins llvmpipe's threads). GL thread only."""
        if self._ctx is None:
            return
        if _EGL is not None and self._egl is not None:
            dpy, ectx = self._egl
            _EGL.eglMakeCurrent(dpy, None, None, None)
            _EGL.eglDestroyContext(dpy, ectx)
            _EGL.eglTerminate(dpy)
            _EGL.eglReleaseThread()
        self._orphans.append(self._ctx)
        self._ctx, self._egl = None, None
        self.epoch += 1

    def release(self, timeout: float | None = 10.0) -> None:
        """Destroy the context now (a later call creates a new one); waits for work in flight."""
        if (self._ctx is None or _EGL is None or self.pid != os.getpid() or self._thread is None
                or not self._thread.is_alive()):
            return
        if threading.get_ident() == self._ident:
            self._teardown()
            return
        fut: Future = Future()
        self._jobs.put((fut, self._teardown, (), {}))
        fut.result(timeout)


    def _park_for_fork(self, timeout: float = 60.0) -> None:
        """Before a fork: finish the work in flight, tear the context down, and hold the GL thread
        idle until the fork is done (so no other thread's render recreates the context meanwhile)."""
        if self.pid != os.getpid() or self._thread is None or not self._thread.is_alive() or _EGL is None:
            return
        if threading.get_ident() == self._ident:  # forking from inside a GL job: nothing else runs now
            self._teardown()
            return
        parked, resume = threading.Event(), threading.Event()

        def park() -> None:
            try:
                self._teardown()
            finally:
                parked.set()
                resume.wait()

        self._resume = resume
        self._jobs.put((Future(), park, (), {}))
        parked.wait(timeout)  # past it, the fork goes on and the child reports a ContextError

    def _unpark(self) -> None:
        """After a fork, in the parent: let the GL thread take work again."""
        if self._resume is not None:
            self._resume.set()
            self._resume = None


class CurrentContext:
    """A context someone else made current on their thread (a window): GL work runs inline."""

    epoch = 1

    def __init__(self, ctx: moderngl.Context) -> None:
        self._ctx = ctx
        self._lock = threading.RLock()

    @property
    def ctx(self) -> moderngl.Context:
        return self._ctx

    def call(self, fn: Callable[..., T], *args: Any, **kwargs: Any) -> T:
        """Run ``fn`` now, on the calling thread (which must be the one the context is current on)."""
        with self._lock:
            return fn(*args, **kwargs)


_EGL = _load_egl()
_threads: "weakref.WeakSet[GLThread]" = weakref.WeakSet()
_shared: GLThread | None = None
_shared_lock = threading.Lock()


def gl_thread() -> GLThread:
    """The process's shared GL thread (its context is created on first use)."""
    global _shared
    if _shared is None:
        with _shared_lock:
            if _shared is None:
                _shared = GLThread()
    return _shared


def headless_context() -> moderngl.Context:
    """The shared EGL context. It lives on the GL thread: use it through ``gl_thread().call``."""
    return gl_thread().ctx


def egl_proc_address(name: str) -> int | None:
    """The address of GL function ``name`` through EGL (None without libEGL or the function)."""
    if _EGL is None:
        return None
    get = _EGL.eglGetProcAddress
    get.restype, get.argtypes = ctypes.c_void_p, [ctypes.c_char_p]
    return get(name.encode()) or None


def egl_current() -> bool:
    """Whether an EGL context is current on the calling thread."""
    return _EGL is not None and bool(_EGL.eglGetCurrentContext())


def _gl_finish_fn() -> Callable[[], None] | None:
    address = egl_proc_address("glFinish")
    return ctypes.CFUNCTYPE(None)(address) if address else None


_GL_FINISH = _gl_finish_fn()


def finish(ctx: moderngl.Context) -> None:
    """Wait for the GL work queued on the calling (GL) thread's context, letting other Python
    threads run meanwhile: moderngl holds the GIL while it waits (in ctx.finish() or a read),
    a ctypes call does not, so numpy work on another thread overlaps llvmpipe's rasterizing.
    (A context EGL did not make, e.g. a window's, waits through moderngl.)"""
    if _GL_FINISH is not None and _EGL.eglGetCurrentContext():
        _GL_FINISH()
    else:
        ctx.finish()


def describe(ctx: moderngl.Context) -> str:
    """One line naming the GL implementation, e.g. 'llvmpipe (LLVM 15.0.6) / OpenGL 4.5'."""
    info = ctx.info
    return f"{info.get('GL_RENDERER', '?')} / {info.get('GL_VERSION', '?')}"


def _before_fork() -> None:
    for t in list(_threads):
        t._park_for_fork()


def _after_fork_in_parent() -> None:
    for t in list(_threads):
        t._unpark()


def _after_fork_in_child() -> None:
    global _shared_lock
    _shared_lock = threading.Lock()
    for t in list(_threads):
        if t._ctx is None:  # torn down before the fork: start afresh
            t._reset()
            t.epoch += 1
        # else the parent's context could not be torn down: t.pid stays the parent's, and the
        # child's first GL call raises a ContextError instead of hanging




def _at_exit() -> None:
    for t in list(_threads):
        try:
            t.release(timeout=5.0)
        except Exception:  # noqa: BLE001 - exiting anyway
            pass


os.register_at_fork(before=_before_fork, after_in_parent=_after_fork_in_parent, after_in_child=_after_fork_in_child)
atexit.register(_at_exit)
