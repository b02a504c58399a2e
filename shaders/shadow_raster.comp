#version 450
// --shadow-raster compute: one invocation per caster triangle of one cascade's draw. It covers the
// texel centres inside the triangle with the hardware's rules (vertices snapped to its sub-texel grid,
// exact integer edge functions, top-left fill rule in memory rows, which are GL's window y), and
// writes the plain path's depth there: the plane's depth at the texel centre plus the slope bias
// (glPolygonOffset's factor x max |dz/dx|, |dz/dy|), clamped to [0, 1] as depth clamp does, by
// atomicMin of its float bits (non-negative floats order as their bits). Triangles whose box
// exceeds uLargeTexels in x or y are appended, in clip space, to a draw the hardware makes plainly:
// their long loops would stall a wave, and their snapped coordinates could overflow 32-bit edges.
layout(local_size_x = 64) in;

layout(r32ui, binding = 0) uniform coherent uimage2D uDepth;
// lp::Vertex: LP_VERTEX_FLOATS floats (set by the pass from sizeof(Vertex)), position first.
layout(std430, binding = 0) readonly buffer Vertices { float vertexData[]; };
layout(std430, binding = 1) readonly buffer Indices { uint indexData[]; };
struct DrawArraysCommand {
    uint count;
    uint instanceCount;
    uint first;
    uint baseInstance;
};
layout(std430, binding = 2) buffer LargeDraws { DrawArraysCommand largeDraws[]; };
layout(std430, binding = 3) writeonly buffer LargeVertices { vec4 largeVertices[]; };

uniform mat4 uModelToClip;
uniform uint uFirstIndex;
uniform uint uTriangleCount;
uniform ivec2 uTileOrigin;
uniform int uTileSize;
uniform int uCascade;
uniform int uDepthZeroToOne;
uniform float uSlopeBias;
uniform float uLargeTexels;
uniform bool uSnappedDepthPlane;  // engine/gl/raster_probe: the raster interpolates from snapped vertices

uniform int uSubTexel;  // 2^GL_SUBPIXEL_BITS: the sub-texel grid the hardware snaps vertices to

vec4 clipPosition(uint index) {
    uint b = index * uint(LP_VERTEX_FLOATS);
    return uModelToClip * vec4(vertexData[b], vertexData[b + 1u], vertexData[b + 2u], 1.0);
}

// Window position in the atlas as the viewport transform gives it (x_w = x_ndc * w/2 + (x + w/2),
// the tile's viewport), rounded as the hardware rounds it: the tile's origin is added before any
// rounding, so snapping below sees the same values as the hardware raster wherever the tile lies.
vec3 atlasWindowPosition(vec4 clip) {
    vec3 ndc = clip.xyz / clip.w;
    float h = 0.5 * float(uTileSize);
    return vec3(ndc.xy * h + (vec2(uTileOrigin) + h), uDepthZeroToOne == 1 ? ndc.z : ndc.z * 0.5 + 0.5);
}

// Edge a->b of a counter-clockwise triangle: positive inside. Its x coefficient is a.y - b.y and
// its y coefficient b.x - a.x; a centre exactly on it is covered when the edge is a left edge
// (inside increases with x) or a horizontal edge with the inside at larger y (memory's "top").
int edgeValue(ivec2 a, ivec2 b, ivec2 p) { return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x); }
bool edgeIncludesZero(ivec2 a, ivec2 b) {
    int cx = a.y - b.y, cy = b.x - a.x;
    return cx > 0 || (cx == 0 && cy > 0);
}
bool inside(int e, bool includeZero) { return e > 0 || (e == 0 && includeZero); }

void main() {
    uint t = gl_GlobalInvocationID.x;
    if (t >= uTriangleCount) return;
    uint first = uFirstIndex + 3u * t;
    vec4 c0 = clipPosition(indexData[first]), c1 = clipPosition(indexData[first + 1u]),
         c2 = clipPosition(indexData[first + 2u]);
    vec3 a0 = atlasWindowPosition(c0), a1 = atlasWindowPosition(c1), a2 = atlasWindowPosition(c2);
    // Tile-local positions (subtracting the whole-texel origin is exact).
    vec3 w0 = vec3(a0.xy - vec2(uTileOrigin), a0.z), w1 = vec3(a1.xy - vec2(uTileOrigin), a1.z),
         w2 = vec3(a2.xy - vec2(uTileOrigin), a2.z);
    vec2 lo = min(w0.xy, min(w1.xy, w2.xy)), hi = max(w0.xy, max(w1.xy, w2.xy));
    if (!(all(greaterThan(hi, vec2(0.0))) && all(lessThan(lo, vec2(float(uTileSize)))))) return;  // off the tile, or NaN
    if (hi.x - lo.x > uLargeTexels || hi.y - lo.y > uLargeTexels) {
        uint slot = atomicAdd(largeDraws[uCascade].count, 3u) + largeDraws[uCascade].first;
        largeVertices[slot] = c0;
        largeVertices[slot + 1u] = c1;
        largeVertices[slot + 2u] = c2;
        return;
    }
    // Texel centres (i + 0.5) inside the box, clamped to the tile.
    ivec2 first2 = max(ivec2(ceil(lo - 0.5)), ivec2(0));
    ivec2 last2 = min(ivec2(floor(hi - 0.5)), ivec2(uTileSize - 1));
    if (any(greaterThan(first2, last2))) return;

    // Snapped on the atlas's window grid, then made tile-local (whole texels: exact integers).
    ivec2 o = uTileOrigin * uSubTexel;
    ivec2 v0 = ivec2(round(a0.xy * float(uSubTexel))) - o, v1 = ivec2(round(a1.xy * float(uSubTexel))) - o,
          v2 = ivec2(round(a2.xy * float(uSubTexel))) - o;
    int area = edgeValue(v0, v1, v2);
    if (area == 0) return;  // degenerate after snapping: the hardware draws nothing
    if (area < 0) {  // both windings cast (no culling): make it counter-clockwise
        ivec2 tmp = v1;
        v1 = v2;
        v2 = tmp;
    }
    bool z01 = edgeIncludesZero(v0, v1), z12 = edgeIncludesZero(v1, v2), z20 = edgeIncludesZero(v2, v0);

    // The depth plane through the window positions the hardware interpolates from: the snapped ones
    // where engine/gl/raster_probe measured that it does (NVIDIA), else the given ones (llvmpipe).
    if (uSnappedDepthPlane) {
        ivec2 a = area < 0 ? v2 : v1, c = area < 0 ? v1 : v2;  // undo the winding swap above
        w0.xy = vec2(v0) / float(uSubTexel);
        w1.xy = vec2(a) / float(uSubTexel);
        w2.xy = vec2(c) / float(uSubTexel);
    }
    vec3 e1 = w1 - w0, e2 = w2 - w0;
    float det = e1.x * e2.y - e2.x * e1.y;
    if (det == 0.0) return;
    float dzdx = (e1.z * e2.y - e2.z * e1.y) / det;
    float dzdy = (e2.z * e1.x - e1.z * e2.x) / det;
    float bias = uSlopeBias * max(abs(dzdx), abs(dzdy));

    for (int y = first2.y; y <= last2.y; ++y) {
        for (int x = first2.x; x <= last2.x; ++x) {
            ivec2 p = ivec2(x, y) * uSubTexel + uSubTexel / 2;
            if (!inside(edgeValue(v0, v1, p), z01) || !inside(edgeValue(v1, v2, p), z12) ||
                !inside(edgeValue(v2, v0, p), z20))
                continue;
            float z = w0.z + dzdx * (float(x) + 0.5 - w0.x) + dzdy * (float(y) + 0.5 - w0.y) + bias;
            z = z > 0.0 ? min(z, 1.0) : 0.0;  // depth clamp; never -0.0, whose bits order last
            imageAtomicMin(uDepth, uTileOrigin + ivec2(x, y), floatBitsToUint(z));
        }
    }
}
