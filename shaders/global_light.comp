#version 450
// Directional lights with normalised Blinn-Phong, plus a constant ambient, into the HDR buffer.
#include "common/brdf.glsl"
#include "common/tonemap.glsl"
#include "common/gbuffer_layout.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = LP_BIND_DEPTH) uniform sampler2D uDepth;
layout(binding = LP_BIND_NORMAL) uniform sampler2D uNormal;
layout(binding = LP_BIND_DIFFUSE) uniform sampler2D uDiffuse;
layout(binding = LP_BIND_POSITION) uniform sampler2D uPosition;
layout(binding = LP_BIND_SPECULAR) uniform sampler2D uSpecular;
layout(rgba16f, binding = 0) uniform writeonly image2D uHdr;

const int MAX_LIGHTS = 16;
uniform int uLightCount;
uniform vec3 uLightDirEye[MAX_LIGHTS];   // towards the light, eye space, unit
uniform vec3 uLightIrradiance[MAX_LIGHTS];
uniform vec3 uAmbient;
uniform bool uLightingOnly;  // debug: white albedo, so the image shows light alone

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uHdr);
    if (p.x >= size.x || p.y >= size.y) return;
    float depth = texelFetch(uDepth, p, 0).r;
    if (depth >= 1.0) {
        imageStore(uHdr, p, vec4(0.0));  // background: the sky pass fills it
        return;
    }
    vec3 N = texelFetch(uNormal, p, 0).xyz;
    vec3 P = texelFetch(uPosition, p, 0).xyz;
    vec4 spec = texelFetch(uSpecular, p, 0);
    vec3 kd = uLightingOnly ? vec3(1.0) : texelFetch(uDiffuse, p, 0).rgb;
    vec3 ks = spec.rgb;
    float pl = length(P);
    vec3 V = pl > 0.0 ? -P / pl : vec3(0.0, 0.0, 1.0);
    vec3 c = uAmbient * kd;
    for (int i = 0; i < uLightCount; ++i)
        c += blinnPhongRadiance(N, V, uLightDirEye[i], kd, ks, spec.a, uLightIrradiance[i]);
    imageStore(uHdr, p, vec4(sanitizeHdr(c), 1.0));
}
