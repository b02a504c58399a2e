#version 450
// Equirectangular map -> cubemap face texels (world space: the scene's rotation about +Y applied).
// Each texel averages taps x taps bilinear samples of the map so small faces don't alias.
#include "common/ibl.glsl"
#include "common/tonemap.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(binding = 0) uniform sampler2D uEquirect;
layout(rgba16f, binding = 0) uniform writeonly imageCube uCube;
uniform int uSize;
uniform int uTaps;
uniform float uRotation;  // radians about +Y

void main() {
    ivec3 p = ivec3(gl_GlobalInvocationID);
    if (p.x >= uSize || p.y >= uSize) return;
    vec3 sum = vec3(0.0);
    for (int j = 0; j < uTaps; ++j)
        for (int i = 0; i < uTaps; ++i) {
            vec2 st = (vec2(p.xy) + (vec2(i, j) + 0.5) / float(uTaps)) / float(uSize) * 2.0 - 1.0;
            vec3 d = rotateY(cubeDirection(p.z, st), -uRotation);
            sum += textureLod(uEquirect, equirectUv(d), 0.0).rgb;
        }
    // sanitizeHdr: values above the half-float maximum (a sun of 86,528) are clamped to 65,504.
    imageStore(uCube, p, vec4(sanitizeHdr(sum / float(uTaps * uTaps)), 1.0));
}
