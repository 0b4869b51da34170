"""Values as users write them, checked: numbers, vectors, colours and axes.

The bottom layer of sdfgl: it imports nothing of sdfgl but the exception types of
:mod:`sdfgl.errors`, so a camera, a light or a settings check does not load the scene
graph. Every check raises :class:`sdfgl.ParameterError` naming the node (or setting) and
the parameter at fault.

- :mod:`.validate`: finite scalars and vectors, live-parameter re-checks
- :mod:`.colors`: colours as names, hex strings, 0..255 integers or 0..1 floats
- :mod:`.axes`: axes as ``"x"``, ``sg.X`` or any vector
- :mod:`.live`: the base type of values that change after a node is built
- :mod:`.float32`: the range of the shader's numbers
"""
