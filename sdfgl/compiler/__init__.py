"""The compiler: scene graph -> GLSL.

- :mod:`.source`: the generated text (``ShaderSource``) and float formatting, the leaf that
  :mod:`sdfgl.gl` imports (this package's ``__init__`` imports nothing, so importing the
  leaf loads nothing else of the compiler);
- :mod:`.emitter`: the ``Emitter`` that nodes write their code into, and :mod:`.tables`
  (the data texture, the moving origin's offsets);
- :mod:`.analysis`: scene frame, closed-form shapes, moving origin, shared subtrees,
  material channels; :mod:`.defines`: the #define block;
- :mod:`.generate` (``generate``, ``compile``) with :mod:`.targets` (the table from target to
  stages) and :mod:`.builder`: the shader itself;
- :mod:`.data`: the data strategies (unions in grid cells or a BVH, ray entry, polygon grids).
"""
