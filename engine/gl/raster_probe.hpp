#pragma once
// How this GPU's rasteriser interpolates: from the vertices as given, or from the vertices snapped
// to its sub-pixel grid (GL_SUBPIXEL_BITS). GL leaves it to the implementation; Mesa's llvmpipe
// interpolates from the unsnapped triangle, NVIDIA from the snapped one. Passes that redo the
// raster's arithmetic in compute (the shadow compute rasteriser, the visibility buffer's resolve)
// follow the measured model, so they agree with the hardware to rounding on either.
#include "engine/gl/shader.hpp"

namespace lp::gl {

struct RasterInterpolation {
    int subpixelBits = 8;             // GL_SUBPIXEL_BITS (at least 4 by the spec)
    bool fromSnappedVertices = false;  // measured: the snapped triangle's depth plane fits the raster's
    // Sum of |depth - plane| over the probe's texels for either model (what decided it).
    double unsnappedError = 0.0, snappedError = 0.0;
    float snapScale() const { return fromSnappedVertices ? float(1 << subpixelBits) : 0.0f; }
};

// Draws one triangle with a steep depth slope and off-grid vertices into a 32x32 depth texture and
// compares its depth with both models' planes. Needs a current context; restores the GL state it
// changes. It waits for the read-back: callers probe once and keep the result.
RasterInterpolation probeRasterInterpolation(const ShaderLibrary& shaders);

}  // namespace lp::gl
