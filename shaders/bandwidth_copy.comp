#version 450
// Streams one RGBA32F image into another: the measured bandwidth sets the compute passes' floors.
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) uniform readonly image2D uSrc;
layout(rgba32f, binding = 1) uniform writeonly image2D uDst;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(uSrc)))) return;
    imageStore(uDst, p, imageLoad(uSrc, p) * 1.0001);
}
