// The scene's colour field at points (texels of uPoints), for vertex colours.
uniform sampler2D uPoints;
layout(location = 0) out vec4 outValue;

void main() {
    vec3 p = texelFetch(uPoints, ivec2(gl_FragCoord.xy), 0).xyz;
    outValue = vec4(mapColor(p), 1.0);
}
