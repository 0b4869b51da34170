// A material channel (EVAL_CHANNEL: mapColor, mapSurface or mapEmission) and map() at
// arbitrary points: texel (x, y) of uPoints holds a point, the output (channel, distance) there.
uniform sampler2D uPoints;
layout(location = 0) out vec4 outValue;

void main() {
    vec3 p = texelFetch(uPoints, ivec2(gl_FragCoord.xy), 0).xyz;
    outValue = vec4(EVAL_CHANNEL(p), map(p));
}
