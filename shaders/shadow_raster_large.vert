#version 450
// --shadow-raster compute: the triangles too large for the compute rasteriser, already in the
// cascade's clip space (shadow_raster.comp appended them); drawn plainly with the polygon offset.
layout(std430, binding = 3) readonly buffer LargeVertices { vec4 largeVertices[]; };
void main() { gl_Position = largeVertices[gl_VertexID]; }
