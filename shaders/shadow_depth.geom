#version 450
// Conservative caster rasterisation: each triangle is grown by half a texel (its edges pushed out by
// half the texel's extent along their normals, Hasselgren et al., GPU Gems 2 ch. 42), so every texel
// the triangle touches is covered. Otherwise a texel whose centre lies just past a silhouette edge
// holds no caster even where two casters meet in a closed concave corner, and receivers next to the
// crease read it as lit (issue #16). The fragment shader clips the grown triangle to its bounding
// box (a sliver's grown corners reach far) and writes the nearest depth over the texel.
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

uniform vec4 uViewport;        // x, y, width, height of the cascade's tile in the atlas (texels)
uniform int uDepthZeroToOne;   // 1 when clip depth is 0..1 (glClipControl), else -1..1

flat out vec4 vTexelBounds;    // window xy min, max of the triangle grown by half a texel
flat out vec2 vDepthRange;     // the triangle's nearest and farthest window depth
flat out int vFacesAway;       // 1: the triangle faces away from the light (window winding clockwise)
flat out vec2 vTriangle[3];    // its window xy before growing: which texel centres it covers
#ifdef LP_SHADOW_ALPHA_TEST
// Alpha-tested casters: the vertex attributes carried to the grown vertices along the triangle's
// planes (extrapolated), so a texel the growth adds reads the alpha the triangle would have there.
layout(location = 1) in ShadowCasterAlpha {
    vec2 uv;
    vec2 uv1;
    vec4 color;
    vec3 objectPosition;
} casterIn[];
layout(location = 1) out ShadowCasterAlpha {
    vec2 uv;
    vec2 uv1;
    vec4 color;
    vec3 objectPosition;
} casterOut;
#endif

float cross2(vec2 a, vec2 b) { return a.x * b.y - a.y * b.x; }

void main() {
    vec2 p[3];
    float z[3];
    for (int i = 0; i < 3; ++i) {
        vec4 c = gl_in[i].gl_Position;  // orthographic light: w = 1
        p[i] = (c.xy / c.w * 0.5 + 0.5) * uViewport.zw + uViewport.xy;
        z[i] = c.z / c.w;
    }
    float area = cross2(p[1] - p[0], p[2] - p[0]);
    if (area == 0.0) return;  // edge-on to the light: its neighbours' grown edges cover it
#ifdef LP_SHADOW_AWAY_ONLY
    // --shadow-raster split: the faces towards the light are drawn plainly in a draw of their own.
    if (area > 0.0) return;
#endif
    float orientation = sign(area);

    // Edge i runs from p[i] to p[i+1]; its outward normal n and offset c (n.x = c inside, pushed out).
    vec2 n[3];
    float c[3];
    for (int i = 0; i < 3; ++i) {
        vec2 e = p[(i + 1) % 3] - p[i];
        n[i] = normalize(orientation * vec2(e.y, -e.x));
        c[i] = dot(n[i], p[i]) + 0.5 * (abs(n[i].x) + abs(n[i].y));
    }
    // Clip depth as a plane over window xy, to carry the grown vertices' depth along it.
    vec2 e1 = p[1] - p[0], e2 = p[2] - p[0];
    float dz1 = z[1] - z[0], dz2 = z[2] - z[0];
    vec2 gradZ = vec2(dz1 * e2.y - dz2 * e1.y, dz2 * e1.x - dz1 * e2.x) / area;

    vec2 lo = min(p[0], min(p[1], p[2])) - 0.5, hi = max(p[0], max(p[1], p[2])) + 0.5;
    vec2 zRange = vec2(min(z[0], min(z[1], z[2])), max(z[0], max(z[1], z[2])));
    vec2 depthRange = uDepthZeroToOne == 1 ? zRange : zRange * 0.5 + 0.5;
    for (int i = 0; i < 3; ++i) {
        // Grown vertex i: where the pushed-out edges i-1 and i meet.
        int j = (i + 2) % 3;
        float det = cross2(n[j], n[i]);
        vec2 q = vec2(c[j] * n[i].y - c[i] * n[j].y, n[j].x * c[i] - n[i].x * c[j]) / det;
        float zq = z[0] + dot(gradZ, q - p[0]);
#ifdef LP_SHADOW_ALPHA_TEST
        // q's barycentric coordinates in the original triangle (outside it: some negative).
        float b1 = cross2(q - p[0], e2) / area, b2 = cross2(e1, q - p[0]) / area, b0 = 1.0 - b1 - b2;
        casterOut.uv = b0 * casterIn[0].uv + b1 * casterIn[1].uv + b2 * casterIn[2].uv;
        casterOut.uv1 = b0 * casterIn[0].uv1 + b1 * casterIn[1].uv1 + b2 * casterIn[2].uv1;
        casterOut.color = b0 * casterIn[0].color + b1 * casterIn[1].color + b2 * casterIn[2].color;
        casterOut.objectPosition =
            b0 * casterIn[0].objectPosition + b1 * casterIn[1].objectPosition + b2 * casterIn[2].objectPosition;
#endif
        vec2 ndc = (q - uViewport.xy) / uViewport.zw * 2.0 - 1.0;
        gl_Position = vec4(ndc, zq, 1.0);
        vTexelBounds = vec4(lo, hi);
        vDepthRange = depthRange;
        vFacesAway = area < 0.0 ? 1 : 0;
        vTriangle = p;
        EmitVertex();
    }
    EndPrimitive();
}
