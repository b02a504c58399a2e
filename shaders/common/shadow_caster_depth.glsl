// The depth a conservatively rasterised shadow caster writes in one texel (issue #16), shared by the
// geometry-shader path (shadow_depth.geom) and the hardware one (GL_NV_conservative_raster), so both
// write the same depths. Window units: xy in texels, depth in [0, 1].

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
