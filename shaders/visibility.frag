#version 450
// gbuffer_visibility: the id of the triangle this fragment belongs to (common/visibility.glsl), drawn
// with gbuffer.vert. With LP_VISIBILITY_ALPHA_MASK the material's alpha test of gbuffer.frag
// (common/material.glsl, the same texture footprint) decides first.
#include "common/visibility.glsl"
#include "common/material.glsl"

uniform uint uFirstTriangle;  // the draw's first global triangle
layout(location = 0) out uint outId;

#ifdef LP_VISIBILITY_ALPHA_MASK
#include "common/vertex_uvs.glsl"
#include "common/vertex_color.glsl"
uniform vec3 uDiffuse;
uniform float uOpacity;
uniform bool uHasDiffuseMap;
uniform float uAlphaCutoff;
uniform uint uSecondUvMaps;
#endif

void main() {
#ifdef LP_VISIBILITY_ALPHA_MASK
    UvSets uvs = fragmentUvSets();
    MaterialInputs m;
    m.diffuse = uDiffuse;
    m.opacity = uOpacity;
    m.hasDiffuseMap = uHasDiffuseMap;
    m.alphaMask = true;
    m.alphaCutoff = uAlphaCutoff;
    m.secondUvMaps = uSecondUvMaps;
    if (materialAlphaRejects(m, materialBaseColor(m, uvs, vColor))) discard;
#endif
    outId = visibilityPackId(uFirstTriangle, uint(gl_PrimitiveID));
}
