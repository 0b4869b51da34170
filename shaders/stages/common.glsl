// Camera, pixel footprint, scene clipping and the hit test, shared by every marcher.
uniform vec2 uResolution;   // framebuffer size in pixels
uniform vec3 uEye;          // ray origin, relative to the shader origin
uniform vec3 uRight;        // camera basis (unit vectors)
uniform vec3 uUp;
uniform vec3 uForward;
uniform float uTanHalfFov;  // tan(vertical fov / 2)
uniform vec2 uJitter;       // sub-pixel offset of the whole image (0 for a still frame)
uniform int uZero;          // always 0: loops starting at uZero cannot be unrolled, so the
                            // compiler keeps one copy of map() per loop, not one per tap

// Angle one pixel subtends at the eye: a ray's footprint at distance t is t * pixelAngle().
float pixelAngle() {
    return 2.0 * uTanHalfFov / uResolution.y;
}

#ifdef ORTHOGRAPHIC
uniform float uOrthoHalfHeight;  // half the view's height in world units

// Width of one pixel at ray parameter t (the same everywhere: parallel rays).
float footprint(float t) {
    return 2.0 * uOrthoHalfHeight / uResolution.y;
}

// Origin of the ray through window position fragCoord: on the image plane through the eye.
vec3 rayOrigin(vec2 fragCoord) {
    vec2 ndc = (2.0 * (fragCoord + uJitter) - uResolution) / uResolution.y;
    return uEye + uOrthoHalfHeight * (ndc.x * uRight + ndc.y * uUp);
}

vec3 rayDir(vec2 fragCoord) {
    return uForward;
}
#else
float footprint(float t) {
    return pixelAngle() * t;
}

vec3 rayOrigin(vec2 fragCoord) {
    return uEye;
}

// Unit direction through window position fragCoord (pixel centres at +0.5, y up).
vec3 rayDir(vec2 fragCoord) {
    vec2 ndc = (2.0 * (fragCoord + uJitter) - uResolution) / uResolution.y;
    return normalize(uForward + uTanHalfFov * (ndc.x * uRight + ndc.y * uUp));
}
#endif

// The part [tmin, tmax] of the ray inside the scene's bounding box (tmin > tmax: miss).
vec2 sceneRange(vec3 ro, vec3 rd) {
    vec3 safe = rd + vec3(equal(rd, vec3(0.0))) * 1e-30;
    vec3 inv = 1.0 / safe;
    vec3 t0 = (BOUNDS_LO - ro) * inv;
    vec3 t1 = (BOUNDS_HI - ro) * inv;
    vec3 tn = min(t0, t1);
    vec3 tf = max(t0, t1);
    float tmin = max(max(tn.x, tn.y), max(tn.z, 0.0));
    float tmax = min(min(tf.x, tf.y), min(tf.z, MAX_DIST));
    return vec2(tmin, tmax);
}

// The height above the surface of ambient occlusion's sample i, of five (0..4: stages/ao.glsl);
// the coarse pass proves AO 1 on a tile out to the farthest (coarse_cone.glsl's tileGroundLit).
float aoSampleHeight(int i) {
    return (0.01 + 0.12 * float(i) / 4.0) * SCENE_SCALE * 0.5;
}

// Distance below which a sample at ray parameter t counts as a hit.
float hitEpsilon(float t) {
#if defined(HIT_CONE)
    return max(HIT_SCALE * footprint(t), 1e-7 * SCENE_SCALE);
#elif defined(HIT_RELATIVE)
    return max(HIT_SCALE * t, 1e-7 * SCENE_SCALE);
#else
    return HIT_SCALE;
#endif
}
