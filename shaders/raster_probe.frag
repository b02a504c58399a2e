#version 450
// engine/gl/raster_probe.cpp: depth only.
void main() {}
