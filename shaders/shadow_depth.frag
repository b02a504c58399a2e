#version 450
// Depth-only pass of conservatively rasterised casters. A triangle facing away from the light keeps,
// in every texel it touches, the nearest depth its plane reaches over the texel (not the depth at
// the texel's centre): a closed concave corner's shadowed side is cast by such a face, so a texel
// that it only partly covers still occludes the receiver behind that part. Faces towards the light
// are the lit receivers themselves: they keep the centre depth that the receivers' plane bias
// (shadow.glsl) expects, so a flat lit surface never shadows itself (common/shadow_caster_depth.glsl),
// where they cover the texel's centre; grown past their edge they yield to a face that covers it.
// Every depth is marked with whether a face towards the light covers its texel's centre.
// LP_SHADOW_CONSERVATIVE: the geometry-shader path (shadow_depth.geom grows the triangle by half a
// texel and passes its box and depth range). LP_SHADOW_HARDWARE_CONSERVATIVE: GL_CONSERVATIVE_-
// RASTERIZATION_NV makes a fragment for every texel the triangle touches; the triangle's vertices
// come from GL_NV_fragment_shader_barycentric. Neither (the plain raster and the spot lights' maps):
// the rasterised depth, with the pass's polygon offset as the slope bias.
#ifdef LP_SHADOW_HARDWARE_CONSERVATIVE
#extension GL_NV_fragment_shader_barycentric : require
#endif
#include "common/shadow_caster_depth.glsl"

// LP_SHADOW_ALPHA_TEST (with any of the above): the MASK and BLEND casters' draws, which first drop
// the fragments whose base colour alpha lets the light through (common/shadow_alpha.glsl).
#ifdef LP_SHADOW_ALPHA_TEST
#include "common/shadow_alpha.glsl"
layout(location = 1) in ShadowCasterAlpha {
    vec2 uv;
    vec2 uv1;
    vec4 color;
    vec3 objectPosition;
} casterIn;
bool casterAlphaDiscards() { return shadowCasterAlphaDiscards(casterIn.uv, casterIn.uv1, casterIn.color, casterIn.objectPosition); }
#else
bool casterAlphaDiscards() { return false; }
#endif

#if defined(LP_SHADOW_CONSERVATIVE)
flat in vec4 vTexelBounds;
flat in vec2 vDepthRange;
flat in int vFacesAway;
flat in vec2 vTriangle[3];  // the triangle before growing (window xy)
uniform float uSlopeBias;  // --shadow-slope-bias: the lit faces' slope-scaled offset (as glPolygonOffset's factor)
uniform float uTexelDepth; // one texel's world size in window depth (the cascade's texel / depth range)

void main() {
    if (casterAlphaDiscards()) discard;
    if (any(lessThan(gl_FragCoord.xy, vTexelBounds.xy)) || any(greaterThan(gl_FragCoord.xy, vTexelBounds.zw))) discard;
    vec2 gradient = vec2(dFdx(gl_FragCoord.z), dFdy(gl_FragCoord.z));
    bool covers = windowPointInTriangle(gl_FragCoord.xy, vTriangle[0], vTriangle[1], vTriangle[2]);
    // Faces away from the light get no slope bias: they are never lit receivers, and pushing them
    // back would undo the half texel that keeps a crease in their shadow.
    float depth = vFacesAway == 0 && !covers
                      ? grownFrontCasterDepth(gl_FragCoord.z, gradient, vDepthRange, uSlopeBias, uTexelDepth)
                      : conservativeCasterDepth(gl_FragCoord.z, gradient, vDepthRange, vFacesAway == 1, uSlopeBias);
    gl_FragDepth = shadowDepthMarked(depth, vFacesAway == 0 && covers);
}
#elif defined(LP_SHADOW_HARDWARE_CONSERVATIVE)
// One draw per facing (the other culled), faces towards the light first, and each promises
// depth_greater (the written depth is never nearer than the rasterised one), so the early depth
// test can reject what lies behind what is already drawn: most faces away from the light lie behind
// the faces towards it of their own mesh.
// Towards the light: the maximum of the caster depth and the rasterised depth (where the texel's
// centre lies past the triangle's farthest vertex the centre depth stays instead of that vertex's).
// Away from it: the nearest depth over the texel, at least the triangle's nearest vertex's. That is
// nearer than the centre, so that draw pulls its rasterised depth nearer still by polygon offset
// (passes/shadow_map_pass.cpp: factor -1.25 >= the texel's half extent (|dz/dx| + |dz/dy|) / 2,
// and a few units for rounding). No clamp to the farthest vertex: in a texel the triangle touches,
// the nearest depth over the texel is at most the depth of a point of the triangle in it.
layout(location = 0) pervertexNV in vec3 vWindow[3];
uniform float uSlopeBias;
uniform float uTexelDepth;  // one texel's world size in window depth
layout(depth_greater) out float gl_FragDepth;

void main() {
    if (casterAlphaDiscards()) discard;
    vec3 a = vWindow[0], b = vWindow[1], c = vWindow[2];
    vec2 range = vec2(min(a.z, min(b.z, c.z)), max(a.z, max(b.z, c.z)));
    // The plane from the vertices, not dFdx/dFdy: exact, and unaffected by depth clamp.
    vec2 gradient = depthPlaneGradient(a, b, c);
#ifdef LP_SHADOW_FACES_AWAY
    // The centre's depth from the plane too: gl_FragCoord.z carries this draw's polygon offset.
    float centre = a.z + dot(gradient, gl_FragCoord.xy - a.xy);
    gl_FragDepth = shadowDepthMarked(conservativeCasterDepth(centre, gradient, vec2(range.x, 1.0), true, uSlopeBias), false);
#else
    bool covers = windowPointInTriangle(gl_FragCoord.xy, a.xy, b.xy, c.xy);
    float depth = covers ? conservativeCasterDepth(gl_FragCoord.z, gradient, range, false, uSlopeBias)
                         : grownFrontCasterDepth(gl_FragCoord.z, gradient, range, uSlopeBias, uTexelDepth);
    gl_FragDepth = shadowDepthMarked(max(depth, gl_FragCoord.z), covers);
#endif
}
#else
void main() {
    if (casterAlphaDiscards()) discard;
}
#endif
