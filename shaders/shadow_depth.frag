#version 450
// Depth-only pass: no colour output, the rasteriser writes depth.
void main() {}
