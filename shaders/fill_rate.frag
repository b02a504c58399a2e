#version 450
// Writes a constant to an RGBA32F target: the fragment path's write bandwidth (raster floors).
layout(location = 0) out vec4 outColor;
void main() { outColor = vec4(gl_FragCoord.xy * 1e-4, 0.5, 1.0); }
