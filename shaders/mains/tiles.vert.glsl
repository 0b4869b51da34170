#version 330 core
// The image drawn tile by tile after the coarse pass: one point the size of a tile per tile of
// pixels (gl_VertexID numbers the tiles, row by row from the bottom), moved off the view where
// the tile is not of the kind this draw covers. The image's program draws the tiles the coarse
// pass left open; the same program without the march draws the tiles it proved empty, and
// without the ground too those where no ray meets the ground. llvmpipe pays for every
// instruction of a fragment shader whatever its branches take, so a pixel must not run code it
// cannot need. (A point, not two triangles: llvmpipe shades the 4x4 blocks a triangle's edge
// crosses once per triangle.) The viewport spans whole tiles, so every tile's centre lies in it.
uniform sampler2D uCoarseStart;  // the coarse pass's tile starts (coarse_cone.glsl)
uniform ivec2 uTiles;            // columns and rows of tiles covering the image
uniform int uTileSide;           // pixels a side of a tile
uniform int uTileKind;           // the kind drawn: 0 open, 1 empty, 2 empty without the ground;
                                 // -1: the whole view, as one triangle (vertices 0..2)

const float EMPTY_START = 1.0e37;  // a start from this on: a tile proven empty (EMPTY_TILE)
const float SKY_START = 2.0e38;    // ... from this on: nor can its rays meet the ground (SKY_TILE)

void main() {
    if (uTileKind < 0) {  // the first frame of an image: one program for every pixel
        vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
        gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
        return;
    }
    ivec2 cell = ivec2(gl_VertexID % uTiles.x, gl_VertexID / uTiles.x);
    float start = texelFetch(uCoarseStart, cell, 0).r;
    int kind = start < EMPTY_START ? 0 : (start < SKY_START ? 1 : 2);
    gl_PointSize = float(uTileSide);
    gl_Position = kind == uTileKind ? vec4((vec2(cell) + 0.5) / vec2(uTiles) * 2.0 - 1.0, 0.0, 1.0)
                                    : vec4(2.0, 2.0, 0.0, 1.0);
}
