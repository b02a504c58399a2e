#version 450
// G-buffer channels as images, decoded from any layout (common/gbuffer_layout.glsl). Values are
// written directly (no tone map) so a picked pixel reads back the encoding documented in the README;
// the two colours, diffuse and specular, as the sRGB encoding of their linear value, as colour images
// are: a picked diffuse pixel reads the diffuse target's bytes, the base colour's 8-bit sRGB code.
#define LP_GBUFFER_READ
#include "common/gbuffer_layout.glsl"
#include "common/tonemap.glsl"
#include "common/velocity.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 12) uniform sampler2D uChannel;  // texcoords (7), the shadow-map atlas (8), tangents (12), velocity (13), AO (14), material input (15, 16)
layout(rgba8, binding = 0) uniform writeonly image2D uLdr;

// 1 depth, 2 normals, 3 diffuse, 4 position, 5 shininess, 6 specular, 7 texcoords, 8 shadow map,
// 9 world position, 10 eye vector, 11 depth fitted to the scene's range, 12 tangent, 13 velocity, 14 ambient
// occlusion (1 white = unoccluded; the sky is 1), 15 gbuffer.material_input as it is (metallic, roughness,
// occlusion: grey), 16 gbuffer.material_input's sRGB encoding (the base colour, as an image shows it)
uniform int uMode;
uniform float uNear;
uniform float uFar;
uniform float uPositionScale;  // 1 / (scene extent), maps eye-space positions into [-1, 1]
uniform ivec2 uShadowGrid;     // mode 8: cascade tiles (columns, rows) of the atlas
uniform mat4 uEyeToWorld;      // modes 9, 10
uniform vec3 uSceneCenter;     // mode 9: the scene's bounds, mapped into [0, 1]
uniform float uSceneHalfSize;  // mode 9: half the longest side of the bounds
uniform vec2 uDepthRange;      // mode 11: eye depth of the scene's nearest and farthest bound
uniform vec2 uOutputSize;      // mode 13: velocity (uv per frame) x this = output pixels per frame
uniform float uVelocityFullScale;  // mode 13: output pixels per frame shown at full brightness

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uLdr);
    if (p.x >= size.x || p.y >= size.y) return;
    if (uMode == 8) {
        // The light's shadow-map atlas (cascade 0 bottom left, one square tile per cascade),
        // fitted into the image with its aspect kept: light-space window depth as grey, 1 = no caster.
        // Outside the atlas: dark blue.
        ivec2 atlas = textureSize(uChannel, 0);
        float scale = min(float(size.x) / float(atlas.x), float(size.y) / float(atlas.y));
        vec2 offset = 0.5 * (vec2(size) - vec2(atlas) * scale);
        vec2 a = (vec2(p) + 0.5 - offset) / scale;
        vec3 grey = vec3(0.0, 0.0, 0.15);
        if (all(greaterThanEqual(a, vec2(0.0))) && all(lessThan(a, vec2(atlas)))) {
            grey = vec3(texelFetch(uChannel, clamp(ivec2(a), ivec2(0), atlas - 1), 0).r);
            // A red line one image pixel wide where cascade tiles meet.
            vec2 tile = vec2(atlas) / vec2(max(uShadowGrid, ivec2(1)));
            vec2 inTile = mod(a, tile);
            vec2 edge = min(inTile, tile - inTile) * scale;
            if ((uShadowGrid.x > 1 && edge.x < 0.5 && a.x > 1.0 && a.x < float(atlas.x) - 1.0) ||
                (uShadowGrid.y > 1 && edge.y < 0.5 && a.y > 1.0 && a.y < float(atlas.y) - 1.0))
                grey = vec3(1.0, 0.0, 0.0);
        }
        imageStore(uLdr, p, vec4(grey, 1.0));
        return;
    }
    if (uMode == 7) {
        imageStore(uLdr, p, vec4(fract(texelFetch(uChannel, p, 0).xy), 0.0, 1.0));
        return;
    }
    if (uMode == 14) {
        imageStore(uLdr, p, vec4(vec3(texelFetch(uChannel, p, 0).r), 1.0));
        return;
    }
    if (uMode == 15 || uMode == 16) {  // background 0 (black)
        vec3 c = clamp(texelFetch(uChannel, p, 0).rgb, 0.0, 1.0);
        imageStore(uLdr, p, vec4(uMode == 16 ? linearToSrgb(c) : c, 1.0));
        return;
    }
    if (uMode == 12) {  // stored encoded by the G-buffer (t x 0.5 + 0.5); the background is cleared to 0
        imageStore(uLdr, p, vec4(texelFetch(uChannel, p, 0).rgb, 1.0));
        return;
    }
    if (uMode == 13) {  // motion: hue is its direction, brightness its length (common/velocity.glsl)
        vec2 v = texelFetch(uChannel, p, 0).xy * uOutputSize;
        imageStore(uLdr, p, vec4(velocityViewColour(v, uVelocityFullScale), 1.0));
        return;
    }
    bool background = gbufferIsBackground(p);
    vec3 c = vec3(0.0);
    if (uMode == 1) {
        // Eye distance along the view axis -> [0, 1] between near and far; background 1.
        float zEye = -gbufferEyeZ(p);
        c = vec3(background ? 1.0 : clamp((zEye - uNear) / (uFar - uNear), 0.0, 1.0));
    } else if (uMode == 11) {
        // The same, over the depth range the scene's bounds span from this camera: a far plane much
        // beyond the scene no longer crushes it into black.
        float zEye = -gbufferEyeZ(p);
        c = vec3(background ? 1.0 : clamp((zEye - uDepthRange.x) / max(uDepthRange.y - uDepthRange.x, 1e-6), 0.0, 1.0));
    } else if (background) {
        c = vec3(0.0);
    } else if (uMode == 2) {
        c = gbufferNormal(p) * 0.5 + 0.5;
    } else if (uMode == 3) {
        c = linearToSrgb(gbufferDiffuse(p));
    } else if (uMode == 4) {
        c = clamp(gbufferPosition(p) * uPositionScale * 0.5 + 0.5, 0.0, 1.0);
    } else if (uMode == 5) {
        c = vec3(clamp(gbufferShininess(p) / 1024.0, 0.0, 1.0));
    } else if (uMode == 6) {
        c = linearToSrgb(gbufferSpecular(p));
    } else if (uMode == 9) {
        vec3 world = (uEyeToWorld * vec4(gbufferPosition(p), 1.0)).xyz;
        c = clamp((world - uSceneCenter) / uSceneHalfSize * 0.5 + 0.5, 0.0, 1.0);
    } else if (uMode == 10) {
        // From the surface towards the eye, in world space.
        c = normalize(mat3(uEyeToWorld) * -gbufferPosition(p)) * 0.5 + 0.5;
    }
    imageStore(uLdr, p, vec4(c, 1.0));
}
