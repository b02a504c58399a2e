// The depth a conservatively rasterised shadow caster writes in one texel (issue #16), shared by the
// geometry-shader path (shadow_depth.geom) and the hardware one (GL_NV_conservative_raster), so both
// write the same depths, and what each depth says about the texel's centre (read by
// common/shadow.glsl). Window units: xy in texels, depth in [0, 1].
#ifndef LP_SHADOW_CASTER_DEPTH_GLSL
#define LP_SHADOW_CASTER_DEPTH_GLSL

// The gradient (dz/dx, dz/dy) of the depth plane through a triangle's three window-space vertices
// (xy, depth). vec2(0) for a triangle of zero area (edge-on to the light: no plane over xy).
vec2 depthPlaneGradient(vec3 a, vec3 b, vec3 c) {
    vec2 e1 = b.xy - a.xy, e2 = c.xy - a.xy;
    float area = e1.x * e2.y - e1.y * e2.x;
    if (area == 0.0) return vec2(0.0);
    float dz1 = b.z - a.z, dz2 = c.z - a.z;
    return vec2(dz1 * e2.y - dz2 * e1.y, dz2 * e1.x - dz1 * e2.x) / area;
}

// A caster's depth in a texel it touches, from the plane's depth at the texel's centre and its
// gradient. Faces away from the light (they cast the shadow in a closed crease) keep the nearest
// depth their plane reaches over the texel (its nearest corner: centre - (|dz/dx| + |dz/dy|) / 2),
// so a texel they only partly cover still occludes what lies behind that part. Faces towards the
// light are lit receivers: their centre depth plus the slope-scaled bias (glPolygonOffset's factor x
// max(|dz/dx|, |dz/dy|)). Both are clamped to the triangle's own depth range (nearest, farthest
// vertex): a sliver's plane runs far past its vertices within one texel.
float conservativeCasterDepth(float centreDepth, vec2 gradient, vec2 depthRange, bool facesAway, float slopeBias) {
    vec2 g = abs(gradient);
    float depth = facesAway ? centreDepth - 0.5 * (g.x + g.y) : centreDepth + slopeBias * max(g.x, g.y);
    return clamp(depth, depthRange.x, depthRange.y);
}

// The depth a face towards the light writes in a texel whose centre it does not cover (it touches the
// texel only because it is grown: the silhouettes and thin casters that conservative coverage keeps).
// It yields to any face that covers the centre, which writes its centre depth plus the slope bias:
// this one writes the farthest depth its plane reaches over the texel past that, plus texelDepth
// (one texel's world size in window depth), more than a tessellated curved surface's next facet
// departs from this one's plane within half a texel (up to about 2 radians between facets). So a
// texel where front faces meet holds the one at its centre, and a grown front face holds a texel
// only where no front face covers its centre. Never nearer than the triangle's nearest vertex.
float grownFrontCasterDepth(float centreDepth, vec2 gradient, vec2 depthRange, float slopeBias, float texelDepth) {
    vec2 g = abs(gradient);
    return max(centreDepth + slopeBias * max(g.x, g.y) + 0.5 * (g.x + g.y) + texelDepth, depthRange.x);
}

// Whether window point p lies in the triangle a, b, c (either winding; its edges included).
bool windowPointInTriangle(vec2 p, vec2 a, vec2 b, vec2 c) {
    float e0 = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
    float e1 = (c.x - b.x) * (p.y - b.y) - (c.y - b.y) * (p.x - b.x);
    float e2 = (a.x - c.x) * (p.y - c.y) - (a.y - c.y) * (p.x - c.x);
    return (e0 >= 0.0 && e1 >= 0.0 && e2 >= 0.0) || (e0 <= 0.0 && e1 <= 0.0 && e2 <= 0.0);
}

// What a texel's depth says about its centre: --shadow-raster conservative draws every caster through
// this file, and each depth it writes carries in its lowest bit whether a face towards the light
// covers the texel's centre (0) or not (1: a face turned away from the light, or a face grown past
// its edge). Only a texel of the first kind can show a lit receiver where the filter compares it;
// the shadow filter needs that at a closed crease, where the texels past the crease hold only the
// grown edges of the two faces (common/shadow.glsl). The depth is rounded up to the next float with
// that bit, at most one ulp farther (6e-8 at depth 0.5, far under any bias): never nearer, so a draw
// that promises depth_greater keeps its promise. A depth past 1 clamps to 1: no caster (the depth
// range is padded, so no caster lies there).
float shadowDepthMarked(float depth, bool frontAtCentre) {
    uint bits = floatBitsToUint(clamp(depth, 0.0, 1.0));
    return (bits & 1u) == (frontAtCentre ? 0u : 1u) ? uintBitsToFloat(bits) : uintBitsToFloat(bits + 1u);
}

// Whether an atlas depth written by shadowDepthMarked has a face towards the light at its texel's centre.
bool shadowDepthFrontAtCentre(float depth) { return (floatBitsToUint(depth) & 1u) == 0u; }

#endif
