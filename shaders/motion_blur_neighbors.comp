#version 450
// Motion blur, step 2 ("NeighborMax"): each tile's longest half blur vector among its 3 x 3 tiles,
// so a pixel sees blur reaching it from the next tile.
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D uTiles;
layout(rg16f, binding = 0) uniform writeonly image2D uNeighbors;

void main() {
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = textureSize(uTiles, 0);
    if (t.x >= size.x || t.y >= size.y) return;
    vec2 best = vec2(0.0);
    float bestLength = 0.0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = t + ivec2(dx, dy);
            if (q.x < 0 || q.y < 0 || q.x >= size.x || q.y >= size.y) continue;
            vec2 v = texelFetch(uTiles, q, 0).xy;
            float l = dot(v, v);
            if (l > bestLength) {
                bestLength = l;
                best = v;
            }
        }
    imageStore(uNeighbors, t, vec4(best, 0.0, 0.0));
}
