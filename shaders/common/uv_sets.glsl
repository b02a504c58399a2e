// A pixel's texture coordinates: the two uv sets (glTF TEXCOORD_0 and TEXCOORD_1), each with its
// footprint, the derivatives every material sample passes to textureGrad.
#ifndef LP_UV_SETS_GLSL
#define LP_UV_SETS_GLSL

// A material's maps as bits (lp::MaterialMapBit), as MaterialInputs.secondUvMaps names those on the
// second set.
const uint LP_MAP_DIFFUSE = 1u, LP_MAP_BUMP = 2u, LP_MAP_NORMAL = 4u, LP_MAP_METAL_ROUGH = 8u, LP_MAP_OCCLUSION = 16u,
           LP_MAP_EMISSIVE = 32u, LP_MAP_SPECULAR = 64u, LP_MAP_SPECULAR_COLOR = 128u,
           LP_MAP_CLEARCOAT = 256u, LP_MAP_CLEARCOAT_ROUGHNESS = 512u, LP_MAP_CLEARCOAT_NORMAL = 1024u,
           LP_MAP_TRANSMISSION = 2048u, LP_MAP_THICKNESS = 4096u;

struct TexCoord {
    vec2 uv;
    vec2 dx;  // d uv / d window x
    vec2 dy;  // d uv / d window y
#ifdef LP_ANISOTROPY_FROM_GRADIENTS
    // The footprint common/material.glsl's own anisotropic filter takes the level from: the same, or
    // the first pixel's of the pixel's 2x2 quad where the driver's raster takes one level per quad.
    vec2 quadDx;
    vec2 quadDy;
#endif
};

struct UvSets {
    TexCoord set0;  // TEXCOORD_0 (lp::Vertex::uv)
    TexCoord set1;  // TEXCOORD_1 (lp::Vertex::uv1): read by the maps a material's secondUvMaps names
};

#endif
