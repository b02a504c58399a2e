// Every G-buffer normal encoding over the whole sphere on the real driver: worst angular error per
// format against the double-precision input, including the poles, the z = 0 seam, ±0 and denormals.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <glm/glm.hpp>

#include "tests/gl/gl_fixture.hpp"

using lp::test::runGlsl;

namespace {

std::vector<glm::dvec3> sphereCases() {
    std::vector<glm::dvec3> v;
    const int n = 20000;  // Fibonacci sphere: near-uniform coverage
    const double golden = M_PI * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < n; ++i) {
        double z = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1.0 - z * z), phi = golden * i;
        v.push_back({r * std::cos(phi), r * std::sin(phi), z});
    }
    for (int s : {-1, 1}) {  // poles and axes, with signed zeros in the other components
        v.push_back({0.0, 0.0, double(s)});
        v.push_back({-0.0, -0.0, double(s)});
        v.push_back({double(s), 0.0, 0.0});
        v.push_back({double(s), -0.0, -0.0});
        v.push_back({0.0, double(s), -0.0});
    }
    for (int i = 0; i < 720; ++i) {  // the z = 0 seam, exactly on it and a hair off it
        double a = 2.0 * M_PI * i / 720.0;
        for (double z : {0.0, -0.0, 1e-7, -1e-7, 1e-40, -1e-40}) v.push_back({std::cos(a), std::sin(a), z});
    }
    v.push_back({1e-40, 1.0, 0.0});  // denormal components
    v.push_back({1.0, -1e-40, -1e-40});
    v.push_back({1e-38, 1e-38, -1.0});
    for (auto& x : v) {
        double l = glm::length(x);
        x = glm::dvec3(x.x / l, x.y / l, x.z / l);  // keeps the sign of zeros
    }
    return v;
}

struct Result {
    double maxDegrees = 0.0;
    double worstZ = 0.0;
    bool allFinite = true;
};

Result measure(const std::string& body) {
    auto cases = sphereCases();
    std::vector<glm::vec4> in;
    for (const auto& c : cases) in.push_back(glm::vec4(glm::vec3(c), 0.0f));
    auto out = runGlsl({"common/normal_encoding.glsl"}, body, in);
    Result r;
    for (size_t i = 0; i < cases.size(); ++i) {
        glm::dvec3 d(out[i]);
        if (!std::isfinite(d.x) || !std::isfinite(d.y) || !std::isfinite(d.z) || glm::length(d) < 0.5) {
            r.allFinite = false;
            continue;
        }
        double err = std::acos(std::clamp(glm::dot(glm::normalize(d), cases[i]), -1.0, 1.0)) * 180.0 / M_PI;
        if (err > r.maxDegrees) {
            r.maxDegrees = err;
            r.worstZ = cases[i].z;
        }
    }
    return r;
}

void report(const char* name, const Result& r) {
    std::printf("  %-34s max angular error %.6f deg (at z = %.3g)\n", name, r.maxDegrees, r.worstZ);
}

}  // namespace

// Seed 001's packed layout loses the sign of z: a normal facing away comes back mirrored (up to
// 180 degrees wrong). Stated: worst error >= 170 deg, at z < 0.
TEST(NormalEncoding, SeedPackedCannotStoreNegativeZ) {
    Result r = measure("return vec4(seedPackedDecode(seedPackedEncode(x.xyz)), 0.0);");
    report("seed 001 packed (x, y; z rebuilt)", r);
    EXPECT_TRUE(r.allFinite);
    EXPECT_GE(r.maxDegrees, 170.0);
    EXPECT_LT(r.worstZ, 0.0);
}

// The fix (sign of z in the shininess channel's sign bit): fp32 x, y; bound 0.03 deg (fp32 rounding
// of x, y amplified near the seam, where dz = -x dx / z is steep).
TEST(NormalEncoding, SeedPackedWithSignedCarrierIsFixed) {
    Result r = measure(R"(
        float carrier = seedPackedSignedCarrier(x.xyz, 64.0);
        return vec4(seedPackedSignedDecode(seedPackedEncode(x.xyz), carrier), 0.0);)");
    report("seed 001 packed + sign in shininess", r);
    EXPECT_TRUE(r.allFinite);
    EXPECT_LT(r.maxDegrees, 0.03);
}

// Seed 004's two angles (phi, cos theta): fp32 storage within 0.01 deg; RG16F storage within 1.2 deg,
// worst at the poles, where fp16's spacing of cos theta near ±1 (2^-11) is a whole degree of theta.
TEST(NormalEncoding, TwoAngleFp32AndFp16) {
    Result r32 = measure("return vec4(twoAngleDecode(twoAngleEncode(x.xyz)), 0.0);");
    report("seed 004 two-angle, fp32", r32);
    EXPECT_TRUE(r32.allFinite);
    EXPECT_LT(r32.maxDegrees, 0.01);
    Result r16 = measure(
        "vec2 e = unpackHalf2x16(packHalf2x16(twoAngleEncode(x.xyz))); return vec4(twoAngleDecode(e), 0.0);");
    report("seed 004 two-angle, fp16", r16);
    EXPECT_TRUE(r16.allFinite);
    EXPECT_LT(r16.maxDegrees, 1.2);
}

// Octahedral, unquantized fp32: within 1e-3 deg everywhere, seam and poles included.
TEST(NormalEncoding, OctahedralFp32) {
    Result r = measure("return vec4(octahedralDecode(octahedralEncode(x.xyz)), 0.0);");
    report("octahedral fp32", r);
    EXPECT_TRUE(r.allFinite);
    EXPECT_LT(r.maxDegrees, 1e-3);
}

// Octahedral quantized ("precise" rounding): 16 bits <= 0.7 deg, 24 bits <= 0.06 deg,
// 32 bits <= 0.01 deg (measured on llvmpipe: 0.626, 0.046, 0.0071). The error scales with the grid
// spacing 1/(2^(b/2-1)-1), stretched up to ~2x where the octahedron's faces meet.
TEST(NormalEncoding, OctahedralQuantized) {
    const struct {
        float bits;
        double bound;
    } formats[] = {{16.0f, 0.7}, {24.0f, 0.06}, {32.0f, 0.01}};
    for (const auto& f : formats) {
        char body[200];
        std::snprintf(body, sizeof body, "return vec4(octahedralDecode(octahedralEncodeQuantized(x.xyz, %.1f)), 0.0);",
                      double(f.bits));
        Result r = measure(body);
        char name[64];
        std::snprintf(name, sizeof name, "octahedral %d bits", int(f.bits));
        report(name, r);
        EXPECT_TRUE(r.allFinite) << name;
        EXPECT_LT(r.maxDegrees, f.bound) << name;
    }
}
