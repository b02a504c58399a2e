// One headless GL 4.5 context for every GL test (llvmpipe in CI, NVIDIA on the GPU machine).
#include <gtest/gtest.h>

#include <cstdio>

#include "engine/core/error.hpp"
#include "engine/gl/context.hpp"
#include "tests/gl/gl_fixture.hpp"

namespace lp::test {
gl::GpuContext* gContext = nullptr;
}

int main(int argc, char** argv) {
    testing::InitGoogleTest(&argc, argv);
    if (testing::GTEST_FLAG(list_tests)) return RUN_ALL_TESTS();  // ctest's discovery: no context needed
    std::unique_ptr<lp::gl::GpuContext> ctx;
    try {
        ctx = lp::gl::createHeadlessContext();
    } catch (const lp::Error& e) {
        std::fprintf(stderr, "gl_tests: cannot create a headless GL 4.5 context: %s\n", e.what());
        return 1;
    }
    lp::test::gContext = ctx.get();
    std::printf("gl_tests on %s (%s)\n", ctx->info().renderer.c_str(), ctx->info().version.c_str());
    return RUN_ALL_TESTS();
}
