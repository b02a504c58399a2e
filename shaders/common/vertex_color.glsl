// The vertex colour (glTF COLOR_0) as a fragment shader's input vColor, for the programs drawn with
// gbuffer.vert. Only a scene with vertex colours compiles them with LP_VERTEX_COLOR (passes/
// gbuffer_pass.hpp's programForLayout): otherwise vColor is white, and no varying is interpolated.
#ifndef LP_VERTEX_COLOR_GLSL
#define LP_VERTEX_COLOR_GLSL
#ifdef LP_VERTEX_COLOR
in vec4 vColor;
#else
const vec4 vColor = vec4(1.0);
#endif
#endif
