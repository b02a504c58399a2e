// engine/gl/raster_probe: which interpolation model this driver's rasteriser follows. Whichever it
// is, the chosen model must fit the raster's depth to float rounding and the other must not (the
// probe's triangle is placed so that the two differ by far more than rounding).
#include <gtest/gtest.h>

#include <cstdio>

#include "engine/gl/handles.hpp"
#include "engine/gl/raster_probe.hpp"

using namespace lp;

TEST(RasterProbe, OneModelFitsTheRasterisersDepthAndTheOtherDoesNot) {
    const gl::ShaderLibrary shaders;
    const long liveBefore = gl::liveObjectCount();
    const gl::RasterInterpolation r = gl::probeRasterInterpolation(shaders);
    EXPECT_EQ(gl::liveObjectCount(), liveBefore);
    std::printf("GL_SUBPIXEL_BITS %d; summed |depth - plane|: unsnapped %.3g, snapped %.3g -> %s\n", r.subpixelBits,
                r.unsnappedError, r.snappedError, r.fromSnappedVertices ? "snapped" : "unsnapped");
    const double chosen = r.fromSnappedVertices ? r.snappedError : r.unsnappedError;
    const double other = r.fromSnappedVertices ? r.unsnappedError : r.snappedError;
    // About 400 covered texels: float rounding of a depth in [0, 1] is a few 1e-8 each.
    EXPECT_LT(chosen, 1e-4);
    EXPECT_GT(other, 20.0 * chosen + 1e-6);
    EXPECT_GE(r.subpixelBits, 4);
    EXPECT_EQ(r.snapScale(), r.fromSnappedVertices ? float(1 << r.subpixelBits) : 0.0f);
}
