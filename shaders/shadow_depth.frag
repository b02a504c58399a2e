#version 450
// Depth-only pass of conservatively grown casters (shadow_depth.geom). A triangle facing away from
// the light keeps, in every texel it touches, the nearest depth its plane reaches over the texel
// (not the depth at the texel's centre): a closed concave corner's shadowed side is cast by such a
// face, so a texel that it only partly covers still occludes the receiver behind that part. Faces
// towards the light are the lit receivers themselves: they keep the centre depth that the receivers'
// plane bias (shadow.glsl) expects, so a flat lit surface never shadows itself.
// Without LP_SHADOW_CONSERVATIVE (the spot lights' perspective maps, drawn without the geometry
// shader) it writes the rasterised depth and the pass's polygon offset gives the slope bias.
#ifdef LP_SHADOW_CONSERVATIVE
flat in vec4 vTexelBounds;
flat in vec2 vDepthRange;
flat in int vFacesAway;
uniform float uSlopeBias;  // --shadow-slope-bias: the lit faces' slope-scaled offset (as glPolygonOffset's factor)

void main() {
    if (any(lessThan(gl_FragCoord.xy, vTexelBounds.xy)) || any(greaterThan(gl_FragCoord.xy, vTexelBounds.zw))) discard;
    // Never past the triangle's own depth range (a sliver's plane is steep past its vertices).
    // Faces away from the light get no slope bias: they are never lit receivers, and pushing them
    // back would undo the half texel that keeps a crease in their shadow.
    float dx = abs(dFdx(gl_FragCoord.z)), dy = abs(dFdy(gl_FragCoord.z));
    float depth = vFacesAway == 1 ? gl_FragCoord.z - 0.5 * (dx + dy) : gl_FragCoord.z + uSlopeBias * max(dx, dy);
    gl_FragDepth = clamp(depth, vDepthRange.x, vDepthRange.y);
}
#else
void main() {}
#endif
