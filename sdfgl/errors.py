"""Exceptions raised by sdfgl. Every message names the node, parameter or file at fault."""


class SdfglError(Exception):
    """Base class of every error sdfgl raises on purpose."""


class ParameterError(SdfglError, ValueError):
    """A node or a setting was given a value it cannot use."""


class MeshError(ParameterError):
    """A triangle mesh cannot be a field (unreadable, empty, not closed, ...); the message names the file."""


class ShaderCompileError(SdfglError):
    """The GL driver rejected a generated shader; the message names the node behind the failing line."""


class ContextError(SdfglError):
    """No OpenGL context could be created (missing EGL libraries, no display, ...)."""


class SceneFileError(SdfglError):
    """A scene file could not be loaded or does not define a scene."""


class SceneDocumentError(SceneFileError, ValueError):
    """A JSON scene document is malformed; the message starts with the JSON path at fault."""
