#version 330 core
// The image drawn tile by tile after the coarse pass: points the size of a tile (or of a square
// block of 2x2 or 4x4 tiles), moved off the view where the tile is not of the kind this draw
// covers. The image's program draws the tiles the coarse pass left open; the same program
// without the march draws the tiles it proved empty, without the ground's shadows and AO those
// whose ground the pass proved lit and open to the sky, and without the ground too those where
// no ray meets it. llvmpipe pays for every instruction of a fragment shader whatever its
// branches take, so a pixel must not run code it cannot need. (Points, not two triangles:
// llvmpipe shades the 4x4 blocks a triangle's edge crosses once per triangle; larger points
// cost it less a pixel.) An empty kind is drawn first by 4x4 blocks, where all their tiles are
// of the kind, then by 2x2 blocks outside those, then by tiles where neither covers them; open
// tiles tile by tile. The viewport (uView) spans whole 4x4 blocks, so every centre lies in it.
uniform sampler2D uCoarseStart;  // the coarse pass's tile starts (coarse_cone.glsl)
uniform ivec2 uTiles;            // columns and rows of tiles covering the image
uniform int uTileSide;           // pixels a side of a tile
uniform int uTileKind;           // the kind drawn: 0 open, 1 empty, 2 empty without the ground,
                                 // 3 empty with lit ground (no shadow, AO 1);
                                 // -1: the whole view, as one triangle (vertices 0..2)
uniform int uBlock;              // 4, 2: a point per 4x4 or 2x2 block of tiles; 1: a point per tile
uniform ivec2 uView;             // the viewport's size in pixels

const float EMPTY_START = 1.0e37;  // a start from this on: a tile proven empty (EMPTY_TILE)
const float LIT_START = 1.5e38;    // ... from this on: its ground is lit and unoccluded (LIT_TILE)
const float SKY_START = 2.5e38;    // ... from this on: none of its rays meets the ground (SKY_TILE)

int kindOf(ivec2 cell) {
    float start = texelFetch(uCoarseStart, cell, 0).r;
    return start < EMPTY_START ? 0 : (start < LIT_START ? 1 : (start < SKY_START ? 3 : 2));
}

// Whether every tile inside the image of the side x side block ``block`` (in blocks of that
// side) is of kind uTileKind.
bool blockOfKind(ivec2 block, int side) {
    for (int i = 0; i < side * side; i++) {
        ivec2 cell = side * block + ivec2(i % side, i / side);
        if (cell.x < uTiles.x && cell.y < uTiles.y && kindOf(cell) != uTileKind) return false;
    }
    return true;
}

void main() {
    if (uTileKind < 0) {  // the first frame of an image: one program for every pixel
        vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
        gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
        return;
    }
    int across = (uTiles.x + uBlock - 1) / uBlock;
    ivec2 at = ivec2(gl_VertexID % across, gl_VertexID / across);  // in blocks of uBlock tiles
    bool drawn;
    if (uBlock == 4) {
        drawn = blockOfKind(at, 4);
    } else if (uBlock == 2) {
        drawn = blockOfKind(at, 2) && !blockOfKind(at / 2, 4);
    } else {  // a full 4x4 block is made of full 2x2 blocks
        drawn = kindOf(at) == uTileKind && (uTileKind == 0 || !blockOfKind(at / 2, 2));
    }
    float side = float(uBlock * uTileSide);
    gl_PointSize = side;
    gl_Position = drawn ? vec4((vec2(at) + 0.5) * side / vec2(uView) * 2.0 - 1.0, 0.0, 1.0)
                        : vec4(2.0, 2.0, 0.0, 1.0);
}
