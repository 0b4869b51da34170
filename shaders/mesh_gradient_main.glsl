// Value and gradient of the clipped field at points (texels of uPoints): the value at p and
// the tetrahedral central difference of IQ's normal, with spacing uEps.
uniform sampler2D uPoints;
uniform float uEps;
layout(location = 0) out vec4 outValue;  // (gradient, value)

void main() {
    vec3 p = texelFetch(uPoints, ivec2(gl_FragCoord.xy), 0).xyz;
    const vec2 k = vec2(1.0, -1.0);
    float a = clippedMap(p + k.xyy * uEps);
    float b = clippedMap(p + k.yyx * uEps);
    float c = clippedMap(p + k.yxy * uEps);
    float d = clippedMap(p + k.xxx * uEps);
    vec3 g = (k.xyy * a + k.yyx * b + k.yxy * c + k.xxx * d) / (4.0 * uEps);
    outValue = vec4(g, clippedMap(p));
}
