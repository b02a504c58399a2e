#version 450
// One triangle over the screen; the G-buffer pass draws it before the meshes into the velocity
// target alone, so pixels no mesh covers get the motion of the background at infinity.
out vec2 vNdc;  // this pixel's jittered NDC
void main() {
    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2) * 2.0 - 1.0;
    vNdc = p;
    gl_Position = vec4(p, 0.0, 1.0);
}
