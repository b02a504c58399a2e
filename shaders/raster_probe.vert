#version 450
// engine/gl/raster_probe.cpp: one triangle given in NDC (w = 1), no vertex buffer.
uniform vec3 uNdc[3];
void main() { gl_Position = vec4(uNdc[gl_VertexID], 1.0); }
