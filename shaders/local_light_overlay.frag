#version 450
// Flat colour for the overlays: the light's colour at radiance uRadiance (HDR). LP_GLOBE_VELOCITY:
// the globe's motion vector into gbuffer.velocity too (location 1).
#include "common/velocity.glsl"

flat in vec3 vColour;
uniform float uRadiance;
layout(location = 0) out vec4 oColor;
#ifdef LP_GLOBE_VELOCITY
in vec4 vCurrentClip;
in vec4 vPreviousClip;
layout(location = 1) out vec2 oVelocity;
#endif
void main() {
    oColor = vec4(vColour * uRadiance, 1.0);
#ifdef LP_GLOBE_VELOCITY
    oVelocity = velocityFromClip(vCurrentClip, vPreviousClip);
#endif
}
