#version 450
// Flat colour for the overlays: the light's colour at radiance uRadiance (HDR).
flat in vec3 vColour;
uniform float uRadiance;
layout(location = 0) out vec4 oColor;
void main() { oColor = vec4(vColour * uRadiance, 1.0); }
