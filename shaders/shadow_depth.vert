#version 450
// Depth-only: positions into one cascade's light clip space.
layout(location = 0) in vec3 inPosition;
uniform mat4 uModelToClip;
#ifdef LP_SHADOW_HARDWARE_CONSERVATIVE
// The hardware conservative raster's fragment shader reads each triangle's three vertices
// (GL_NV_fragment_shader_barycentric) as window xy (texels) and window depth.
uniform vec4 uViewport;       // x, y, width, height of the cascade's tile in the atlas (texels)
uniform int uDepthZeroToOne;  // 1 when clip depth is 0..1 (glClipControl), else -1..1
layout(location = 0) out vec3 vWindow;
#endif
#ifdef LP_SHADOW_ALPHA_TEST
// Alpha-tested casters (common/shadow_alpha.glsl): what the base colour's alpha and the hashed
// threshold read. Attribute 5 (the second uv set) reads (0, 0) on a mesh without one, whose
// materials never sample it.
layout(location = 2) in vec2 inUv;
layout(location = 4) in vec4 inColor;
layout(location = 5) in vec2 inUv1;
layout(location = 1) out ShadowCasterAlpha {
    vec2 uv;
    vec2 uv1;
    vec4 color;
    vec3 objectPosition;
} casterOut;
#endif
void main() {
    gl_Position = uModelToClip * vec4(inPosition, 1.0);
#ifdef LP_SHADOW_HARDWARE_CONSERVATIVE
    vec3 ndc = gl_Position.xyz / gl_Position.w;  // orthographic light: w = 1
    vWindow = vec3((ndc.xy * 0.5 + 0.5) * uViewport.zw + uViewport.xy, uDepthZeroToOne == 1 ? ndc.z : ndc.z * 0.5 + 0.5);
#endif
#ifdef LP_SHADOW_ALPHA_TEST
    casterOut.uv = inUv;
    casterOut.uv1 = inUv1;
    casterOut.color = inColor;
    casterOut.objectPosition = inPosition;
#endif
}
