// Points (texels of uPoints) moved onto the surface by Newton steps along the gradient, all
// rounds in one draw: each step moves a point by -f grad / |grad|^2, at most uMaxMove (half a
// cell, so a point near a thin wall or a crease stays on its own side), until |f| <= uTol or
// uIterations steps. The move is kept apart from the start point (float32 holds a small move
// exactly enough; the caller adds it to its float64 point).
uniform sampler2D uPoints;
uniform float uEps;
uniform float uTol;
uniform float uMaxMove;
uniform int uIterations;
layout(location = 0) out vec4 outMove;      // (move, gradient evaluations)
layout(location = 1) out vec4 outNormal;  // (unit gradient at the end point, value there)

void main() {
    vec3 p0 = texelFetch(uPoints, ivec2(gl_FragCoord.xy), 0).xyz;
    vec3 move = vec3(0.0);
    float bend;  // unused here
    vec4 gf = clippedGradient(p0, uEps, bend);
    int calls = 1;
    for (int i = 0; i < uIterations && abs(gf.w) > uTol; i++) {
        vec3 d = gf.w / max(dot(gf.xyz, gf.xyz), 1e-12) * gf.xyz;
        d *= min(1.0, uMaxMove / max(length(d), 1e-30));
        move -= d;
        gf = clippedGradient(p0 + move, uEps, bend);
        calls++;
    }
    outMove = vec4(move, float(calls));
    outNormal = vec4(gf.xyz / max(length(gf.xyz), 1e-30), gf.w);
}
