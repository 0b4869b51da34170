// The march of a scene that is one mesh, moved or turned as a whole (sdfgl.compiler.analysis
// ray_free and own_mesh): the ray meets it where it meets its first triangle, so one cast from
// tmin is the march. The map() call asks for the cast alone (gCastOnly: the mesh skips its
// walk) and leaves the way to that triangle in gFree, shortened by MESH_RAY_SLACK for the
// marchers' safety (lib/sd_mesh_bvh.glsl); undone here, it is the ray parameter of the
// (slightly widened) triangle's plane, which no gap between triangles lets the ray slip through.
float march(vec3 ro, vec3 rd, float tmin, float tmax, inout int steps) {
    rayFreeStart(rd);
    gFreeAsk = true;
    gCastOnly = true;
    map(ro + rd * tmin);
    gFreeAsk = false;
    gCastOnly = false;
    steps++;
    float hit = tmin + gFree / (1.0 - MESH_RAY_SLACK);
    return gFree < 3.0e38 && hit <= tmax ? hit : -1.0;
}
