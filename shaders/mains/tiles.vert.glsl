#version 330 core
// The image drawn tile by tile after the coarse pass: one point the size of a tile per tile of
// pixels (gl_VertexID numbers the tiles, row by row from the bottom), moved off the view where
// the tile is not of the kind this draw covers. The image's program draws the tiles the coarse
// pass left open, a program without the march draws the tiles it proved empty. llvmpipe pays
// for every instruction of a fragment shader whatever its branches take, so a pixel that needs
// no march must not run a program that has one. (A point, not two triangles: llvmpipe shades
// the 4x4 blocks a triangle's edge crosses once per triangle.) The viewport spans whole tiles,
// so every tile's centre lies inside it.
uniform sampler2D uCoarseStart;  // the coarse pass's tile starts (coarse_cone.glsl)
uniform ivec2 uTiles;            // columns and rows of tiles covering the image
uniform int uTileSide;           // pixels a side of a tile
uniform int uEmptyTiles;         // 1: draw the tiles proven empty; 0: the others

const float EMPTY_START = 1.0e37;  // a start at least this is a tile proven empty (EMPTY_TILE)

void main() {
    ivec2 cell = ivec2(gl_VertexID % uTiles.x, gl_VertexID / uTiles.x);
    bool empty = texelFetch(uCoarseStart, cell, 0).r >= EMPTY_START;
    gl_PointSize = float(uTileSide);
    gl_Position = empty == (uEmptyTiles == 1) ? vec4((vec2(cell) + 0.5) / vec2(uTiles) * 2.0 - 1.0, 0.0, 1.0)
                                              : vec4(2.0, 2.0, 0.0, 1.0);
}
