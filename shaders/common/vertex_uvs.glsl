// The uv sets as inputs of the fragment shaders drawn with gbuffer.vert: vUv, and vUv1 only where a
// material of the scene samples TEXCOORD_1 (LP_SECOND_UV, set by passes/gbuffer_pass.hpp's
// programForLayout and the forward pass): otherwise no second varying is interpolated, and the
// second set reads the first.
#ifndef LP_VERTEX_UVS_GLSL
#define LP_VERTEX_UVS_GLSL
#include "common/uv_sets.glsl"

in vec2 vUv;
#ifdef LP_SECOND_UV
in vec2 vUv1;
#endif

// The uv of set 1 (second) or set 0.
vec2 fragmentUv(bool second) {
#ifdef LP_SECOND_UV
    return second ? vUv1 : vUv;
#else
    return vUv;
#endif
}

// Both sets with their fine derivatives: call before any discard (they need the whole quad).
UvSets fragmentUvSets() {
    UvSets s;
    s.set0 = TexCoord(vUv, dFdxFine(vUv), dFdyFine(vUv));
#ifdef LP_SECOND_UV
    s.set1 = TexCoord(vUv1, dFdxFine(vUv1), dFdyFine(vUv1));
#else
    s.set1 = s.set0;
#endif
    return s;
}

#endif
