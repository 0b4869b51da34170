// The free way along the ray, for the marchers (RAY_FREE: the scene is one grid union or
// one mesh, perhaps moved as a whole; sdfgl.compiler.analysis.ray_free). The marcher sets
// gRayDir and gRayInv once a ray, and gFreeAsk before each map() call of its march; map()
// leaves in gFree how far along gRayDir from its point the scene is proven empty
// (shaders/templates/grid_ray.glsl, sd_mesh_bvh.glsl's meshRayFree). The marcher may step
// that far at once: the segment is proven empty.
vec3 gRayDir = vec3(0.0, 0.0, 1.0);  // the marcher's ray direction (unit)
vec3 gRayInv = vec3(1.0);            // 1 / gRayDir, set once a ray (a 0 component as 1e-30)
float gFree = 0.0;
bool gFreeAsk = false;               // whether this map() call is the march's (a mesh casts only then)
bool gCastOnly = false;              // the call asks for the cast alone: the scene's own mesh skips its walk

// Set the free way's ray direction (turned into the grid's or mesh's frame where it is rotated).
void rayFreeStart(vec3 rd) {
#ifdef RAY_FREE_TURN
    gRayDir = RAY_FREE_TURN * rd;
#else
    gRayDir = rd;
#endif
    gRayInv = 1.0 / (gRayDir + vec3(equal(gRayDir, vec3(0.0))) * 1e-30);
}
