// map() at arbitrary points: texel (x, y) of uPoints holds a point, the output its value.
uniform sampler2D uPoints;
layout(location = 0) out float outValue;

void main() {
    vec3 p = texelFetch(uPoints, ivec2(gl_FragCoord.xy), 0).xyz;
    outValue = map(p);
}
