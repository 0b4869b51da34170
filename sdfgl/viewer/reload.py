"""Hot reload: the scene file the window shows, loaded again whenever it changes.

A reload's settings are the window's current ones with what the file changed applied
(a setting removed from the file goes back to the window's default) and what the caller
gave explicitly on top. The new scene is shown once it has compiled and drawn: a file
that fails to load, or a program that fails to compile, leaves the last good scene up.

The file is run in a child process with a time limit (:mod:`sdfgl.scenefile_process`), never
on the window's thread: a file that loops, sleeps or ends its process costs the window
nothing, and a reload is polled for while the window keeps answering.
"""
from __future__ import annotations

from pathlib import Path
from typing import Any

from ..nodes.base import IMPLICIT, Node
from ..scenefile import SceneFile
from ..scenefile_process import DEFAULT_TIMEOUT_S, SceneFileLoader
from ..settings import DISTANCE_METHODS, Settings


def window_defaults(scene: Node) -> dict[str, Any]:
    """The window's default settings for ``scene``."""
    base: dict[str, Any] = {"aa": 1, "shadows": "soft", "ao": scene.exactness != IMPLICIT, "ground": False}
    if scene.exactness == IMPLICIT:
        base["method"] = "newton"
    return base


class SceneFileWatch:
    """The scene file at ``path``; ``explicit`` are the settings the caller gave (they win).

    Each load of the file is stopped after ``timeout`` seconds."""

    def __init__(self, path: str | Path, explicit: dict[str, Any], timeout: float = DEFAULT_TIMEOUT_S) -> None:
        self.path = Path(path)
        self.explicit = dict(explicit)
        self.file_settings: dict[str, Any] = {}  # the settings of the file as last shown
        self.mtime = 0.0
        self.loader = SceneFileLoader(timeout)

    def load(self) -> SceneFile:
        """The file's scene, camera and settings now (the window's first scene); waits for the load.

        Raises SceneFileError when the file fails, runs past the time limit or ends its process."""
        mtime = self._mtime()
        sf = self.loader.wait(self.path)
        self.file_settings = sf.settings
        self.mtime = mtime
        return sf

    def _mtime(self) -> float:
        try:
            return self.path.stat().st_mtime
        except OSError:
            return 0.0

    @property
    def loading(self) -> float | None:
        """Seconds the reload in progress has run, or None when none is."""
        return self.loader.elapsed() if self.loader.loading is not None else None

    def changed(self) -> bool:
        """Whether the file was written since it was last loaded (taken as seen: asked once a change)."""
        try:
            mtime = self.path.stat().st_mtime
        except OSError:
            return False
        if mtime == self.mtime:
            return False
        self.mtime = mtime
        return True

    def start_reload(self) -> None:
        """Start loading the file again (a reload still in progress is stopped: the newest wins)."""
        self.loader.start(self.path)

    def poll_reload(self, wanted: dict[str, Any]) -> tuple[Node, dict[str, Any], dict[str, Any]] | None:
        """The finished reload: (scene, the settings to show it with, the file's own settings); None
        while it runs or when none was started. Never blocks.

        ``wanted`` are the window's settings now. Raises SceneFileError when the file failed, ran
        past the time limit or ended its process, and ParameterError for settings it cannot use."""
        sf = self.loader.poll()
        if sf is None:
            return None
        settings = self.reloaded_settings(sf.scene, sf.settings, wanted)
        if sf.scene.exactness == IMPLICIT and settings.get("method", "enhanced") in DISTANCE_METHODS:
            settings.update(method="newton", ao=False)
        Settings.build(**settings)
        return sf.scene, settings, sf.settings

    def reloaded_settings(self, scene: Node, file_settings: dict[str, Any], wanted: dict[str, Any]) -> dict[str, Any]:
        """Settings after a reload: what the file changed applies, key toggles of the rest stay,
        and what the caller gave explicitly wins."""
        new = dict(wanted)
        base = window_defaults(scene)
        for k in set(self.file_settings) - set(file_settings):  # removed from the file: back to the default
            if k in base:
                new[k] = base[k]
            else:
                new.pop(k, None)
        new.update({k: v for k, v in file_settings.items() if k not in self.file_settings
                    or self.file_settings[k] != v})
        new.update(self.explicit)
        return new

    def close(self) -> None:
        """Stop any load in progress and the process kept for the next one."""
        self.loader.close()
