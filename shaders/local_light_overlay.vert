#version 450
// Overlays: mode 0 light volumes (icosphere x bounding sphere, drawn as wireframe), mode 1 light
// globes (icosphere x uGlobeScale x range), mode 2 the outline of light uLightIndex's scissor
// rectangle (uRectNdc = x0, y0, x1, y1; gl_VertexID 0..3 as a line loop).
// LP_GLOBE_VELOCITY (globes only): also the unjittered current and previous clip positions of the
// globe's surface point, which moves rigidly with its light (docs/motion.md).
#include "common/local_light.glsl"

layout(std430, binding = 0) readonly buffer LocalLights { LpLocalLight uLights[]; };
layout(location = 0) in vec3 aPosition;
uniform int uMode;
uniform int uLightIndex;
uniform mat4 uProjection;
uniform float uGlobeScale;
uniform vec4 uRectNdc;
flat out vec3 vColour;  // the light's colour, brightest channel 1
#ifdef LP_GLOBE_VELOCITY
// Per light: world-space centre now (xyz) and at the previous frame's time (orbits move it).
struct LpGlobeMotion {
    vec4 current;
    vec4 previous;
};
layout(std430, binding = 1) readonly buffer GlobeMotion { LpGlobeMotion uGlobeMotion[]; };
uniform mat4 uViewProjection;          // unjittered
uniform mat4 uPreviousViewProjection;  // unjittered
uniform mat3 uWorldFromEyeRotation;
out vec4 vCurrentClip;
out vec4 vPreviousClip;
#endif

void main() {
    int light = uMode == 2 ? uLightIndex : gl_InstanceID;
    vec3 c = uLights[light].intensity.rgb;
    vColour = c / max(max(c.r, max(c.g, c.b)), 1e-20);
    if (uMode == 2) {
        int v = gl_VertexID & 3;
        gl_Position = vec4(v == 0 || v == 3 ? uRectNdc.x : uRectNdc.z, v < 2 ? uRectNdc.y : uRectNdc.w, 0.0, 1.0);
    } else {
        vec4 pr = uMode == 1 ? uLights[light].positionRange : uLights[light].bound;
        float s = uMode == 1 ? uGlobeScale * pr.w : pr.w;
        gl_Position = uProjection * vec4(pr.xyz + aPosition * s, 1.0);
#ifdef LP_GLOBE_VELOCITY
        vec3 offset = uWorldFromEyeRotation * (aPosition * s);
        vCurrentClip = uViewProjection * vec4(uGlobeMotion[light].current.xyz + offset, 1.0);
        vPreviousClip = uPreviousViewProjection * vec4(uGlobeMotion[light].previous.xyz + offset, 1.0);
#endif
    }
}
