// Value and gradient of the clipped field at points (texels of uPoints), differences uEps wide.
uniform sampler2D uPoints;
uniform float uEps;
layout(location = 0) out vec4 outValue;  // (gradient, value)

void main() {
    outValue = clippedGradient(texelFetch(uPoints, ivec2(gl_FragCoord.xy), 0).xyz, uEps);
}
