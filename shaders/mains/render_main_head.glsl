// Outputs, the primary-ray trace and the radiance of one sample, used by main() and
// by the debug views.
layout(location = 0) out vec4 outColor;
#ifdef OUT_DEPTH
layout(location = LOC_DEPTH) out float outDepth;
#endif
#ifdef OUT_NORMAL
layout(location = LOC_NORMAL) out vec4 outNormal;
#endif
#ifdef OUT_STEPS
layout(location = LOC_STEPS) out float outSteps;
#endif

struct Hit {
    float t;       // ray parameter of the hit, -1.0 for a miss
    int steps;     // map() evaluations spent
    bool ground;   // the hit is on the analytic ground plane
};

Hit tracePrimary(vec3 ro, vec3 rd) {
    Hit h = Hit(-1.0, 0, false);
    vec2 range = sceneRange(ro, rd);
#ifdef COARSE_TILE
    range.x = max(range.x, coarseStart());  // the tile's cone proved the way before it empty
#endif
#ifdef MESH_DEPTH
    float tm = meshDepth();  // a raster mesh in front ends the march
    range.y = min(range.y, tm);
#endif
#if defined(GROUND) && !defined(SKY_TILES)  // no ray of a sky tile meets the ground
    float tg = groundHit(ro, rd);
#ifdef MESH_DEPTH
    if (tg >= tm) tg = -1.0;
#endif
    if (tg > 0.0) range.y = min(range.y, tg);
#endif
#ifndef EMPTY_TILES  // drawn only where the coarse pass proved the tile empty: no march there
    if (range.x <= range.y) {
        h.t = march(ro, rd, range.x, range.y, h.steps);
        if (isnan(h.t) || isinf(h.t)) h.t = -1.0;  // a field that overflows (x^1000) is no hit, never NaN
    }
#endif
#if defined(GROUND) && !defined(SKY_TILES)
    if (h.t < 0.0 && tg > 0.0) {
        h.t = tg;
        h.ground = true;
    }
#endif
    return h;
}

vec3 hitNormal(vec3 ro, vec3 rd, Hit h) {
#if defined(EMPTY_TILES)
    return vec3(0.0, 1.0, 0.0);  // only the ground can be hit on an empty tile
#else
#ifdef GROUND
    if (h.ground) return vec3(0.0, 1.0, 0.0);
#endif
    return calcNormal(ro + rd * h.t, h.t, rd);
#endif
}

// One shadeSurface() call for the ground and the scene alike: llvmpipe runs the straight code
// of both sides of a branch for every block of pixels, so a second call would cost every
// pixel a second shading. Tiles the coarse pass proved empty meet only the ground: no
// material of the scene there.
vec3 radiance(vec3 ro, vec3 rd, Hit h) {
    if (h.t < 0.0) return background(rd);
    vec3 pos = ro + rd * h.t;
    vec3 nor = hitNormal(ro, rd, h);
#if defined(GROUND) && defined(EMPTY_TILES)
    Surface s = defaultSurface(groundAlbedo(pos));
#elif defined(GROUND)
    Surface s;  // (WebGL: no ?: on structs)
    if (h.ground) s = defaultSurface(groundAlbedo(pos));
    else s = sceneSurface(pos);
#else
    Surface s = sceneSurface(pos);
#endif
    vec3 col = shadeSurface(pos, nor, rd, s, h.t);
#ifdef GROUND
    if (h.ground) col = mix(col, background(rd), 1.0 - exp(-h.t / (SCENE_SCALE * 40.0)));
#endif
    return col;
}

// One sample as (linear colour, coverage). With ALPHA a miss is transparent and the
// colour is premultiplied by coverage, so averaging samples gives coverage-weighted colour.
vec4 sampleColor(vec3 ro, vec3 rd, Hit h) {
#ifdef MESH_DEPTH
    if (h.t < 0.0) {  // the march stopped at a raster mesh, or missed everything
        vec4 mesh = meshColor();
        if (mesh.a > 0.0) return vec4(mesh.rgb, 1.0);
    }
#endif
#ifdef ALPHA
    if (h.t < 0.0) return vec4(0.0);
    float cover = 1.0;
#ifdef FOG_DISTANCE
    cover = exp(-h.t / FOG_DISTANCE);
#endif
    return vec4(radiance(ro, rd, h) * cover, cover);
#else
    vec3 col = radiance(ro, rd, h);
#ifdef FOG_DISTANCE
    if (h.t >= 0.0) col = mix(background(rd), col, exp(-h.t / FOG_DISTANCE));
#endif
    return vec4(col, 1.0);
#endif
}

// The pixel from its averaged samples: gamma-encoded (stages/gamma.glsl), straight (un-premultiplied) alpha.
vec4 pixelColor(vec4 acc) {
#ifdef ALPHA
    vec3 straight = acc.a > 0.0 ? acc.rgb / acc.a : vec3(0.0);
    return vec4(gammaEncode(straight), acc.a);
#else
    return vec4(gammaEncode(acc.rgb), 1.0);
#endif
}
