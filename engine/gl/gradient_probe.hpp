#pragma once
// How this driver samples a texture with textureGrad's explicit gradients, measured. GLSL says the
// gradients give the footprint; Mesa's llvmpipe, where a texture filters anisotropically, takes the
// footprint and its level of detail from the differences of the texture coordinates between the SIMD
// lanes of a 2x2 fragment quad instead (gallivm's lp_build_pmin and lp_build_sample_aniso). In a
// fragment shader that is nearly the same thing (per quad rather than per pixel); in a compute
// shader the lanes are no quad, and the visibility buffer's resolve, which samples every map with
// textureGrad and gradients of its own, read blocks of pixels whole levels away from the raster's.
// Where the compute half of the probe finds this, the resolve filters anisotropically itself
// (shaders/common/material.glsl, LP_ANISOTROPY_FROM_GRADIENTS), choosing the level the way the raster
// half found the driver's fragment path does, so both G-buffer modes pick the same levels.
#include "engine/gl/shader.hpp"

namespace lp::gl {

// Which level(s) an anisotropic sample reads, for a level of detail lambda (numbered as
// material.glsl's uAnisotropyLevels).
enum class AnisotropicLevels {
    Blended = 0,  // the two around lambda, mixed by its fraction (trilinear: GL's LINEAR_MIPMAP_LINEAR)
    Floor = 1,    // level floor(lambda) alone (llvmpipe)
    Nearest = 2,  // level round(lambda) alone
};
const char* anisotropicLevelsName(AnisotropicLevels levels);

struct GradientSampling {
    bool anisotropyAvailable = false;  // EXT_texture_filter_anisotropic; without it nothing below can go wrong
    // Compute: textureGrad through an anisotropic sampler took the level its gradients give.
    bool computeFollowsGradients = true;
    // Raster (a fragment shader's textureGrad of its own derivatives, anisotropy 8): how the level of
    // detail comes from the footprint's axes in texels, Pmax >= Pmin. Clamped: log2(Pmax / min(Pmax /
    // Pmin, max anisotropy)) as EXT_texture_filter_anisotropic has it; else log2(Pmin) at any ratio
    // (llvmpipe: its clamp compares Pmin with itself).
    bool rasterClampsRatio = true;
    AnisotropicLevels rasterLevels = AnisotropicLevels::Blended;
    // The level is taken once per 2x2 quad, from the differences at its first pixel (even x, even y:
    // dFdxCoarse's), rather than from each pixel's own gradients (llvmpipe: lane differences).
    bool rasterLevelPerQuad = false;
    // What was read (4 x red of a texture whose level k is red k / 4), the worst invocation or pixel,
    // farthest from what the gradients ask for: compute, gradients of 4 texels in x and y through an
    // isotropic sampler and through an anisotropic one (level 2), and of 8 x 2 texels (level 1: the
    // ratio 4 is within 8); raster, 3 x 3 texels a pixel (lambda log2 3 = 1.58) and 64 x 2 (ratio 32:
    // lambda 3 clamped, 1 not).
    double computeIsotropic = 0.0, computeSquare = 0.0, computeStretched = 0.0;
    double rasterFractional = 0.0, rasterStretched = 0.0;
    // A uv whose derivatives change from pixel to pixel (gradient_probe.frag's product term): the summed
    // |level read - level predicted| over the 8x8 pixels with each pixel's own gradients and with its
    // quad's first pixel's, under the level model above; the smaller decides rasterLevelPerQuad.
    double rasterPerPixelError = 0.0, rasterPerQuadError = 0.0;
};

// Samples a 16x16 texture of one colour per mip level from one 8x8 compute work group (the visibility
// resolve's shape) and from the fragments of 8x8 full-screen draws. Needs a current context;
// restores the GL state it changes. It waits for the read-backs: callers probe once and keep the result.
GradientSampling probeGradientSampling(const ShaderLibrary& shaders);

}  // namespace lp::gl
