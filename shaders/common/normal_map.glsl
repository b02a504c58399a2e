// Tangent-space normal maps (glTF normalTexture, MTL norm).
#ifndef LP_NORMAL_MAP_GLSL
#define LP_NORMAL_MAP_GLSL

// The shading normal for a decoded tangent-space normal t (texel * 2 - 1) in the unit frame T, B, N:
// x and y scaled by `scale` (glTF normalTexture.scale), then normalised. Falls back to N when the
// result has no length (a zero texel), so it is never NaN.
vec3 normalMapNormal(vec3 N, vec3 T, vec3 B, vec3 t, float scale) {
    vec3 n = vec3(t.xy * scale, t.z);
    vec3 w = T * n.x + B * n.y + N * n.z;
    float l = length(w);
    return l > 1e-20 ? w / l : N;
}

#endif
