"""The look of a render: lights, ambient light, background, transparency and fog.

Everything here becomes generated GLSL (sdfgl.look.shading): a light that is not in
the scene has no code in the shader, and the default rig reproduces the original look
(a warm key light with the ``shadows`` setting's shadow, a sky fill and a back light).
"""
from .lights import DEFAULT_LIGHTS, MAX_LIGHTS, Light, directional_light, point_light
from .background import Background

__all__ = ["Light", "directional_light", "point_light", "DEFAULT_LIGHTS", "MAX_LIGHTS", "Background"]
