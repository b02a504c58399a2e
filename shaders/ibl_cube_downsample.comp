#version 450
// One mip of the environment cube from the level above it: each texel is the solid-angle-weighted
// mean of its 2x2 children, sum(L_i w_i) / sum(w_i) with w_i the child's exact solid angle. A plain
// box filter (glGenerateMipmap) weights every texel alike although a face-centre texel spans 5.2x
// the solid angle of a corner one: in a coarse mip a lamp near a face centre lost up to half its
// energy (and one near a corner gained), which filtered importance sampling then read.
#include "common/ibl.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(rgba16f, binding = 0) uniform readonly imageCube uFiner;
layout(rgba16f, binding = 1) uniform writeonly imageCube uCoarser;
uniform int uFinerSize;

void main() {
    ivec3 p = ivec3(gl_GlobalInvocationID);
    int coarse = max(uFinerSize / 2, 1);
    if (p.x >= coarse || p.y >= coarse) return;
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            ivec2 c = min(2 * p.xy + ivec2(i, j), ivec2(uFinerSize - 1));
            float w = cubeTexelSolidAngle(c, uFinerSize);
            sum += imageLoad(uFiner, ivec3(c, p.z)).rgb * w;
            weight += w;
        }
    imageStore(uCoarser, p, vec4(sum / weight, 1.0));
}
