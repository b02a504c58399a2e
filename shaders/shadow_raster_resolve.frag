#version 450
// --shadow-raster compute: the R32UI depth bits the compute rasteriser wrote become the D32F atlas
// the receivers read (drawn over the whole atlas with the depth test off; cleared texels hold 1.0).
layout(binding = 0) uniform usampler2D uDepthBits;
void main() { gl_FragDepth = uintBitsToFloat(texelFetch(uDepthBits, ivec2(gl_FragCoord.xy), 0).r); }
