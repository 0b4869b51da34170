"""The compiler: scene graph -> GLSL.

- :mod:`.source`: the generated text (:class:`ShaderSource`) and float formatting, the only
  module :mod:`sdfgl.gl` imports;
- :mod:`.emitter`: the :class:`Emitter` that nodes write their code into, and
  :mod:`.tables` (the data texture, the moving origin's offsets);
- :mod:`.analysis`: scene frame, closed-form shapes, moving origin, shared subtrees,
  material channels; :mod:`.defines`: the #define block;
- :mod:`.generate` with :mod:`.targets` (the table from target to stages) and
  :mod:`.builder`: the shader itself;
- :mod:`.data`: the data strategies (unions in grid cells or a BVH, ray entry, polygon grids).
"""
from .generate import compile, generate
from .source import ShaderSource, glsl_float

__all__ = ["ShaderSource", "compile", "generate", "glsl_float"]
