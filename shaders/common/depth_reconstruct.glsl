// Eye-space position rebuilt from the depth buffer instead of stored (saves 16 bytes a pixel).
// Standard depth: GL's [-1, 1] clip z, stored as window depth in [0, 1] (near 0, far 1).
// Reversed-Z: glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE) with near at 1 and far at 0 in a float
// depth buffer, whose dense floats near 0 then fall where perspective needs them (far away).
#ifndef LP_DEPTH_RECONSTRUCT_GLSL
#define LP_DEPTH_RECONSTRUCT_GLSL

// Eye-space z (negative in front of the camera) from standard window depth d in [0, 1].
float eyeZFromStandardDepth(float d, float near, float far) {
    float ndc = d * 2.0 - 1.0;
    return -2.0 * near * far / (far + near - ndc * (far - near));
}

// Eye-space z from reversed-Z depth d in [0, 1] (near -> 1, far -> 0) of an infinite-far-plane-free
// projection with near/far: d = near * (far - zc) / (zc * (far - near)) for distance zc.
float eyeZFromReversedDepth(float d, float near, float far) {
    return -near * far / (near + d * (far - near));
}

// Eye-space position from a pixel's normalised coordinates uv in [0, 1] and its eye z, for a
// symmetric perspective with vertical field of view tanHalfFovY and aspect width/height.
vec3 eyePositionFromZ(vec2 uv, float eyeZ, float tanHalfFovY, float aspect) {
    vec2 ndc = uv * 2.0 - 1.0;
    return vec3(ndc.x * tanHalfFovY * aspect * -eyeZ, ndc.y * tanHalfFovY * -eyeZ, eyeZ);
}

#endif
