// Value and gradient of the clipped field at points (texels of uPoints), differences uEps wide,
// and the stencil's bend (mesh_clip.glsl: large where the stencil straddles a crease).
uniform sampler2D uPoints;
uniform float uEps;
layout(location = 0) out vec4 outValue;  // (gradient, value)
layout(location = 1) out vec4 outBend;   // (bend, 0, 0, 0)

void main() {
    float bend;
    outValue = clippedGradient(texelFetch(uPoints, ivec2(gl_FragCoord.xy), 0).xyz, uEps, bend);
    outBend = vec4(bend, 0.0, 0.0, 0.0);
}
