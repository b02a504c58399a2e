#version 450
// Depth-only pass of conservatively rasterised casters. A triangle facing away from the light keeps,
// in every texel it touches, the nearest depth its plane reaches over the texel (not the depth at
// the texel's centre): a closed concave corner's shadowed side is cast by such a face, so a texel
// that it only partly covers still occludes the receiver behind that part. Faces towards the light
// are the lit receivers themselves: they keep the centre depth that the receivers' plane bias
// (shadow.glsl) expects, so a flat lit surface never shadows itself (common/shadow_caster_depth.glsl).
// LP_SHADOW_CONSERVATIVE: the geometry-shader path (shadow_depth.geom grows the triangle by half a
// texel and passes its box and depth range). LP_SHADOW_HARDWARE_CONSERVATIVE: GL_CONSERVATIVE_-
// RASTERIZATION_NV makes a fragment for every texel the triangle touches; the triangle's vertices
// come from GL_NV_fragment_shader_barycentric. Neither (the plain raster and the spot lights' maps):
// the rasterised depth, with the pass's polygon offset as the slope bias.
#ifdef LP_SHADOW_HARDWARE_CONSERVATIVE
#extension GL_NV_fragment_shader_barycentric : require
#endif
#include "common/shadow_caster_depth.glsl"

#if defined(LP_SHADOW_CONSERVATIVE)
flat in vec4 vTexelBounds;
flat in vec2 vDepthRange;
flat in int vFacesAway;
uniform float uSlopeBias;  // --shadow-slope-bias: the lit faces' slope-scaled offset (as glPolygonOffset's factor)

void main() {
    if (any(lessThan(gl_FragCoord.xy, vTexelBounds.xy)) || any(greaterThan(gl_FragCoord.xy, vTexelBounds.zw))) discard;
    // Faces away from the light get no slope bias: they are never lit receivers, and pushing them
    // back would undo the half texel that keeps a crease in their shadow.
    gl_FragDepth = conservativeCasterDepth(gl_FragCoord.z, vec2(dFdx(gl_FragCoord.z), dFdy(gl_FragCoord.z)), vDepthRange,
                                           vFacesAway == 1, uSlopeBias);
}
#elif defined(LP_SHADOW_HARDWARE_CONSERVATIVE)
// One draw per facing (the other face culled), so each program can say which way its depth moves.
// Towards the light: never nearer than the rasterised depth (max with gl_FragCoord.z: where the
// texel's centre lies past the triangle's farthest vertex the centre depth is kept, not that
// vertex's), so depth_greater holds and the early depth test can reject them as before. Away from
// it: the nearest depth over the texel is nearer than the rasterised one, except where the clamp
// to the triangle's depth range lifts it; no direction holds, so no layout is promised and the
// depth test runs after the shader.
layout(location = 0) pervertexNV in vec3 vWindow[3];
uniform float uSlopeBias;
#ifndef LP_SHADOW_FACES_AWAY
layout(depth_greater) out float gl_FragDepth;
#endif

void main() {
    vec3 a = vWindow[0], b = vWindow[1], c = vWindow[2];
    vec2 range = vec2(min(a.z, min(b.z, c.z)), max(a.z, max(b.z, c.z)));
    // The plane from the vertices, not dFdx/dFdy: exact, and unaffected by depth clamp.
    vec2 gradient = depthPlaneGradient(a, b, c);
#ifdef LP_SHADOW_FACES_AWAY
    gl_FragDepth = conservativeCasterDepth(gl_FragCoord.z, gradient, range, true, uSlopeBias);
#else
    gl_FragDepth = max(conservativeCasterDepth(gl_FragCoord.z, gradient, range, false, uSlopeBias), gl_FragCoord.z);
#endif
}
#else
void main() {}
#endif
