#version 450
// The classic G-buffer pass's background (passes/gbuffer_pass): after the meshes, every pixel whose
// depth kept its cleared value gets what the visibility resolve writes there (common/gbuffer_images'
// storeBackground: zeros, and the background's motion in the velocity target). It replaces clearing
// every colour target and drawing the background's motion in full-screen raster, which the H100 paid
// at its fragment rate: 6.5 of the pass's 12.5 ms at 4K on the Cornell box.
// Defines: gbufferImageDefines (passes/gbuffer_pass.hpp).
#include "common/gbuffer_images.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// gbuffer.depth: uBackgroundDepth where nothing was drawn (the depth test is strict, so a drawn
// fragment never equals it).
layout(binding = 6) uniform sampler2D uDepth;
uniform float uBackgroundDepth;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = textureSize(uDepth, 0);
    if (any(greaterThanEqual(p, size))) return;
    if (texelFetch(uDepth, p, 0).r == uBackgroundDepth) storeBackground(p, vec2(size));
}
