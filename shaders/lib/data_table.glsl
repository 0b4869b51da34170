// Data tables (sdfgl.codegen.Emitter.table): texel i of a table lies at (i % width, i / width).
#define POLY_DATA_WIDTH 1024
#define POLY_DATA_SHIFT 10
