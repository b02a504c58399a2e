// Motion vectors: gbuffer.velocity (RG16F) holds uv_current - uv_previous, uv in [0, 1] over the
// image (u right, v up), from the UNJITTERED current and previous clip positions (jitter does not
// move it). The previous position of the pixel at uv is uv - velocity. docs/motion.md.
#ifndef LP_VELOCITY_GLSL
#define LP_VELOCITY_GLSL

// uv_current - uv_previous of one point from its two clip positions; 0 where either is behind its
// camera (w <= 0: no meaningful previous position). Clamped to +-4 image sizes so a point that was
// almost in the camera's plane cannot overflow the 16-bit target.
vec2 velocityFromClip(vec4 currentClip, vec4 previousClip) {
    if (!(currentClip.w > 1e-9) || !(previousClip.w > 1e-9)) return vec2(0.0);
    vec2 v = 0.5 * (currentClip.xy / currentClip.w - previousClip.xy / previousClip.w);
    return any(isnan(v)) ? vec2(0.0) : clamp(v, vec2(-4.0), vec2(4.0));
}

// Velocity of the background at jittered NDC `ndc`: a direction at infinity, which only the camera's
// rotation moves. inverseRotationProjection = inverse(unjittered projection x view's rotation).
vec2 backgroundVelocity(vec2 ndc, vec2 jitterNdc, mat4 inverseRotationProjection, mat4 viewProjection,
                        mat4 previousViewProjection) {
    vec4 e = inverseRotationProjection * vec4(ndc - jitterNdc, 1.0, 1.0);
    vec4 direction = vec4(e.xyz / e.w, 0.0);
    return velocityFromClip(viewProjection * direction, previousViewProjection * direction);
}

// The velocity view: direction as hue (right red, up yellow-green, left cyan, down violet) and
// length as brightness, linear up to full brightness at fullScalePixels; zero motion is black.
vec3 velocityViewColour(vec2 velocityPixels, float fullScalePixels) {
    float len = length(velocityPixels);
    if (!(len > 0.0) || isinf(len)) return vec3(0.0);
    float hue = fract(atan(velocityPixels.y, velocityPixels.x) / 6.283185307179586);
    vec3 rgb = clamp(abs(fract(hue + vec3(1.0, 2.0 / 3.0, 1.0 / 3.0)) * 6.0 - 3.0) - 1.0, 0.0, 1.0);
    return rgb * min(len / fullScalePixels, 1.0);
}

#endif
