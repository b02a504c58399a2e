#version 450
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec4 inTangent;
#ifdef LP_SECOND_UV  // a material of the scene samples TEXCOORD_1 (common/vertex_uvs.glsl)
layout(location = 5) in vec2 inUv1;
out vec2 vUv1;
#endif
#ifdef LP_VERTEX_COLOR  // the scene has vertex colours (glTF COLOR_0; common/vertex_color.glsl)
layout(location = 4) in vec4 inColor;
out vec4 vColor;      // multiplies the material's base colour and alpha
#endif

uniform mat4 uModelView;
uniform mat3 uNormalMatrix;
uniform mat4 uProjection;

out vec3 vPosition;   // eye space
out vec3 vNormal;     // eye space
out vec2 vUv;
out vec4 vTangent;    // eye space xyz, handedness w
#ifdef LP_GBUFFER_VELOCITY
// Unjittered clip positions this frame and the previous one (common/velocity.glsl).
uniform mat4 uClipFromModel;
uniform mat4 uPreviousClipFromModel;
// The vertex's position in the previous frame: an animated mesh's pose then, else its position
// (GpuMesh::previousPositions; the location is SceneGpu's kPreviousPositionAttribute).
layout(location = LP_PREVIOUS_POSITION_ATTRIBUTE) in vec3 inPreviousPosition;
out vec4 vCurrentClip;
out vec4 vPreviousClip;
#endif
// The emission pass draws with this shader again and tests GL_EQUAL against the G-buffer depth.
invariant gl_Position;

void main() {
    vec4 p = uModelView * vec4(inPosition, 1.0);
    vPosition = p.xyz;
    vNormal = uNormalMatrix * inNormal;
    vTangent = vec4(mat3(uModelView) * inTangent.xyz, inTangent.w);
    vUv = inUv;
#ifdef LP_SECOND_UV
    vUv1 = inUv1;
#endif
#ifdef LP_VERTEX_COLOR
    vColor = inColor;
#endif
    gl_Position = uProjection * p;
#ifdef LP_GBUFFER_VELOCITY
    vCurrentClip = uClipFromModel * vec4(inPosition, 1.0);
    vPreviousClip = uPreviousClipFromModel * vec4(inPreviousPosition, 1.0);
#endif
}
