// Local half-thickness of the solid under surface points (texels of uPoints): samples of the
// clipped field along the inward normal, uStep apart, up to uReach. Under a thin part (a wire, a
// sliver, a small tetrahedron) the field falls to a minimum -r at the part's middle and rises
// again; under a thick part, or inward from a convex edge, it keeps falling. Writes r where the
// field turned (the minimum is followed by a rise of at least uStep / 2) and 0 elsewhere.
uniform sampler2D uPoints;
uniform float uEps;
uniform float uStep;
uniform float uReach;
layout(location = 0) out vec4 outThickness;  // (half-thickness or 0, samples taken, 0, 0)

void main() {
    vec3 p = texelFetch(uPoints, ivec2(gl_FragCoord.xy), 0).xyz;
    float bend;
    vec4 gf = clippedGradient(p, uEps, bend);
    vec3 n = gf.xyz / max(length(gf.xyz), 1e-30);
    float low = 0.0;
    float half_ = 0.0;
    int taken = 5;
    for (float t = uStep; t <= uReach; t += uStep) {
        float f = clippedMap(p - n * t);
        taken++;
        low = min(low, f);
        if (f > low + 0.5 * uStep) {  // turned: the far side of a thin part
            half_ = -low;
            break;
        }
    }
    outThickness = vec4(half_, float(taken), 0.0, 0.0);
}
