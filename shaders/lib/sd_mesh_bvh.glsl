// Exact signed distance to a closed triangle mesh kept as data (sdfgl/compiler/data/triangles.py).
// Node i is 4 texels from `nodes` + 4 i: (lo_a, child_a), (hi_a, child_b), (lo_b, 0), (hi_b, 0);
// a child k >= 0 is node k, k < 0 the leaf of the (-k & 7) triangles from (-k >> 3); both go on
// the walk's stack. Triangle t is 9 texels from `tris` + 9 t: a, b, c (face normal in .w), the
// pseudonormals of edges ab, bc, ca and of vertices a, b, c. The walk visits the nearer child first and skips boxes
// farther than the closest triangle so far; the closest point is Ericson's (Real-Time
// Collision Detection, 5.1.5) with the feature it lies on, whose angle-weighted pseudonormal
// gives the sign (Baerentzen and Aanaes 2005). The closest triangle of the last call
// (meshHint) starts the walk: a ray's map() calls follow each other closely, so it is
// usually still the closest one, or near it, and the walk skips nearly every box from the
// start. The result does not depend on it (every triangle nearer than the hint is still
// found); a hint from another mesh's table is ignored. The ray's cast (meshRayFree) leaves
// the triangle it met as the hint, and its normal where the ray met it (gMeshNormal).
// requires: data_table

float meshBoxDist2(vec3 p, vec3 lo, vec3 hi) {
    vec3 d = max(max(lo - p, p - hi), 0.0);
    return dot(d, d);
}

// The walks' stack (the closest triangle's and the ray's): a child goes on it unless its box
// lies beyond `best` by `key` (the walk's measure of a box: squared distance, or where the ray
// enters it); of two children the farther goes first, so the nearer one is popped next.
#define MESH_PUSH(key, k) if (key < best) { stackNode[sp] = k; stackDist[sp] = key; sp++; }
#define MESH_PUSH_BOTH(keyA, kA, keyB, kB) { float keyN = keyA; float keyF = keyB; int kN = kA; int kF = kB; if (keyF < keyN) { keyN = keyB; keyF = keyA; kN = kB; kF = kA; } MESH_PUSH(keyF, kF) MESH_PUSH(keyN, kN) }

// The boxes of node `code`'s two children: (lo, child code) and (hi, other child's code) of
// the first, (lo, 0) and (hi, 0) of the second.
void meshNodeBoxes(int nodes, int code, out vec4 loA, out vec4 hiA, out vec4 loB, out vec4 hiB) {
    int at = nodes + 4 * code;
    loA = dataFetch(at);
    hiA = dataFetch(at + 1);
    loB = dataFetch(at + 2);
    hiB = dataFetch(at + 3);
}

// The point of triangle abc closest to p; `feature`: 0 the face, 1..3 vertex a, b, c,
// 4..6 edge ab, bc, ca.
vec3 meshClosest(vec3 p, vec3 a, vec3 b, vec3 c, out int feature) {
    vec3 ab = b - a;
    vec3 ac = c - a;
    vec3 ap = p - a;
    float d1 = dot(ab, ap);
    float d2 = dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) { feature = 1; return a; }
    vec3 bp = p - b;
    float d3 = dot(ab, bp);
    float d4 = dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) { feature = 2; return b; }
    float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) { feature = 4; return a + ab * (d1 / (d1 - d3)); }
    vec3 cp = p - c;
    float d5 = dot(ab, cp);
    float d6 = dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) { feature = 3; return c; }
    float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) { feature = 6; return a + ac * (d2 / (d2 - d6)); }
    float va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
        feature = 5;
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    feature = 0;
    float denom = 1.0 / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

// Keep triangle record t if it is closer than the closest so far: its squared distance,
// record, feature and point.
void meshTriangle(vec3 p, int t, inout float best, inout int bestTri, inout int bestFeature, inout vec3 bestPoint) {
    int feature;
    vec3 q = meshClosest(p, dataFetch(t).xyz, dataFetch(t + 1).xyz, dataFetch(t + 2).xyz, feature);
    vec3 w = p - q;
    float d2 = dot(w, w);
    if (d2 < best) {
        best = d2;
        bestTri = t;
        bestFeature = feature;
        bestPoint = q;
    }
}

// The triangles of leaf `code` (< 0), without a loop: llvmpipe ends every loop of a shader
// invocation once their rounds together pass 65535, and a ray calls map() hundreds of times
// (leaves are popped from the walk's stack like nodes, so this is written out once).
void meshLeaf(vec3 p, int tris, int code, inout float best, inout int bestTri, inout int bestFeature,
              inout vec3 bestPoint) {
    int t = tris + 9 * ((-code) >> 3);
    int count = (-code) & 7;
    meshTriangle(p, t, best, bestTri, bestFeature, bestPoint);
    if (count > 1) meshTriangle(p, t + 9, best, bestTri, bestFeature, bestPoint);
    if (count > 2) meshTriangle(p, t + 18, best, bestTri, bestFeature, bestPoint);
    if (count > 3) meshTriangle(p, t + 27, best, bestTri, bestFeature, bestPoint);
}

// The unit pseudonormal of triangle record t at `feature` (meshClosest's): the face's normal,
// or the record's edge or vertex pseudonormal.
vec3 meshFeatureNormal(int t, int feature) {
    if (feature == 0) return vec3(dataFetch(t).w, dataFetch(t + 1).w, dataFetch(t + 2).w);
    return dataFetch(t + (feature <= 3 ? 5 + feature : feature - 1)).xyz;
}

int meshHint = -1;  // the texel of the triangle record closest to the last point asked
// The surface normal at the last point asked's closest point (the pseudonormal of the
// feature it lies on), or, after a cast, where the ray met the mesh: the normal at a hit
// on a lone mesh, no walk of its own (stages/normal.glsl).
vec3 gMeshNormal = vec3(0.0, 1.0, 0.0);

// `trisEnd`: the texel after the mesh's last triangle record.
float sdMeshBVH(vec3 p, int nodes, int tris, int trisEnd) {
    float best = 3.0e38;
    int bestTri = tris;
    int bestFeature = 0;
    vec3 bestPoint = p;
    if (meshHint >= tris && meshHint < trisEnd) meshTriangle(p, meshHint, best, bestTri, bestFeature, bestPoint);
    int stackNode[32];
    float stackDist[32];
    int sp = 1;
    stackNode[0] = 0;
    stackDist[0] = 0.0;
    while (sp > 0) {  // an entry: a node (code >= 0) or a leaf (code < 0), with its box's distance
        sp--;
        int code = stackNode[sp];
        if (stackDist[sp] < best && code < 0) {
            meshLeaf(p, tris, code, best, bestTri, bestFeature, bestPoint);
        } else if (stackDist[sp] < best) {
            vec4 loA, hiA, loB, hiB;
            meshNodeBoxes(nodes, code, loA, hiA, loB, hiB);
            float keyA = meshBoxDist2(p, loA.xyz, hiA.xyz);
            float keyB = meshBoxDist2(p, loB.xyz, hiB.xyz);
            MESH_PUSH_BOTH(keyA, int(loA.w), keyB, int(hiA.w))
        }
    }
    meshHint = bestTri;
    gMeshNormal = meshFeatureNormal(bestTri, bestFeature);
    return dot(p - bestPoint, gMeshNormal) < 0.0 ? -sqrt(best) : sqrt(best);
}

// Where the ray from p along unit d (inv = 1 / d) first meets a triangle of the mesh, or
// 3e38 where it meets none: the free way along the ray (lib/ray_free.glsl). The walk
// visits the nearer box first and skips boxes the ray enters beyond the nearest hit so
// far. Each triangle is widened by MESH_RAY_SLACK of its edges (barycentric) and each box
// by as much of the scene, so a ray through an edge or a vertex, which float32 may let
// slip between the triangles that share it, still meets one; a hit is taken a little
// early for the same reason. The way is therefore never longer than the true one.
#define MESH_RAY_SLACK 1e-4

float meshRayBox(vec3 p, vec3 inv, vec3 lo, vec3 hi, float pad) {
    vec3 a = (lo - pad - p) * inv;
    vec3 b = (hi + pad - p) * inv;
    vec3 near = min(a, b);
    vec3 far = max(a, b);
    float enter = max(max(near.x, near.y), max(near.z, 0.0));
    float leave = min(min(far.x, far.y), far.z);
    return leave < enter ? 3.0e38 : enter;
}

// Moller-Trumbore against triangle record t, widened: the ray parameter of the hit or 3e38.
float meshRayTriangle(vec3 p, vec3 d, int t) {
    vec3 a = dataFetch(t).xyz;
    vec3 e1 = dataFetch(t + 1).xyz - a;
    vec3 e2 = dataFetch(t + 2).xyz - a;
    vec3 pv = cross(d, e2);
    float det = dot(e1, pv);
    if (abs(det) < 1e-30) return 3.0e38;
    float inv = 1.0 / det;
    vec3 tv = p - a;
    float u = dot(tv, pv) * inv;
    vec3 qv = cross(tv, e1);
    float v = dot(d, qv) * inv;
    float s = dot(e2, qv) * inv;
    bool inside = u >= -MESH_RAY_SLACK && v >= -MESH_RAY_SLACK && u + v <= 1.0 + MESH_RAY_SLACK;
    return inside && s >= 0.0 ? s : 3.0e38;
}

// Keep triangle record t if the ray meets it nearer than the nearest hit so far.
void meshRayKeep(vec3 p, vec3 d, int t, inout float best, inout int bestTri) {
    float s = meshRayTriangle(p, d, t);
    if (s < best) {
        best = s;
        bestTri = t;
    }
}

void meshRayLeaf(vec3 p, vec3 d, int tris, int code, inout float best, inout int bestTri) {
    int t = tris + 9 * ((-code) >> 3);
    int count = (-code) & 7;
    meshRayKeep(p, d, t, best, bestTri);
    if (count > 1) meshRayKeep(p, d, t + 9, best, bestTri);
    if (count > 2) meshRayKeep(p, d, t + 18, best, bestTri);
    if (count > 3) meshRayKeep(p, d, t + 27, best, bestTri);
}

float meshRayFree(vec3 p, vec3 d, vec3 inv, int nodes, int tris, float pad) {
    float best = 3.0e38;
    int bestTri = -1;
    int stackNode[32];
    float stackDist[32];
    int sp = 1;
    stackNode[0] = 0;
    stackDist[0] = 0.0;
    while (sp > 0) {
        sp--;
        int code = stackNode[sp];
        if (stackDist[sp] < best && code < 0) {
            meshRayLeaf(p, d, tris, code, best, bestTri);
        } else if (stackDist[sp] < best) {
            vec4 loA, hiA, loB, hiB;
            meshNodeBoxes(nodes, code, loA, hiA, loB, hiB);
            float keyA = meshRayBox(p, inv, loA.xyz, hiA.xyz, pad);
            float keyB = meshRayBox(p, inv, loB.xyz, hiB.xyz, pad);
            MESH_PUSH_BOTH(keyA, int(loA.w), keyB, int(hiA.w))
        }
    }
    if (bestTri < 0) return best;
    int feature;  // where on the triangle the ray met it: its normal there
    meshClosest(p + d * best, dataFetch(bestTri).xyz, dataFetch(bestTri + 1).xyz, dataFetch(bestTri + 2).xyz, feature);
    gMeshNormal = meshFeatureNormal(bestTri, feature);
    meshHint = bestTri;
    return best * (1.0 - MESH_RAY_SLACK);
}
