#version 450
// Fills the pixels no geometry covered (depth at the far plane) with the background: the
// environment cubemap in the view direction, or the plain colour when the scene has no map.
#include "common/tonemap.glsl"
#define LP_GBUFFER_READ
#include "common/gbuffer_layout.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 7) uniform samplerCube uEnvironment;
layout(rgba16f, binding = 0) uniform image2D uHdr;
uniform vec3 uColor;
uniform bool uHasMap;
uniform float uIntensity;
uniform mat4 uInvProjection;
uniform mat3 uEyeToWorld;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uHdr);
    if (p.x >= size.x || p.y >= size.y) return;
    if (!gbufferIsBackground(p)) return;
    vec3 c = uColor;
    if (uHasMap) {
        vec2 ndc = (vec2(p) + 0.5) / vec2(size) * 2.0 - 1.0;
        vec4 e = uInvProjection * vec4(ndc, 1.0, 1.0);
        vec3 dir = normalize(uEyeToWorld * (e.xyz / e.w));
        c = textureLod(uEnvironment, dir, 0.0).rgb * uIntensity;
    }
    imageStore(uHdr, p, vec4(sanitizeHdr(c), 1.0));
}
