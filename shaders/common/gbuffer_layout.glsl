// The G-buffer's texture bindings as every full-screen pass sees them (the seeds' unpacked layout):
//   depth     D32F      window-space depth
//   normal    RGBA32F   eye-space unit normal in xyz
//   diffuse   RGBA8     diffuse albedo (linear)
//   position  RGBA32F   eye-space position in xyz
//   specular  RGBA16F   specular colour in rgb, Blinn-Phong shininess in a
//   texcoord  RG32F     texture coordinates (only when a debug view asks for them)
#ifndef LP_GBUFFER_LAYOUT_GLSL
#define LP_GBUFFER_LAYOUT_GLSL
#define LP_BIND_DEPTH 0
#define LP_BIND_NORMAL 1
#define LP_BIND_DIFFUSE 2
#define LP_BIND_POSITION 3
#define LP_BIND_SPECULAR 4
#define LP_BIND_TEXCOORD 5
#define LP_BIND_HDR 6
#endif
