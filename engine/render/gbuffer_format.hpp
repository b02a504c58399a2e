#pragma once
// How the G-buffer stores normals and positions (--gbuffer, --gbuffer-position). Every pass reads
// the G-buffer through the one decode API of shaders/common/gbuffer_layout.glsl, compiled with
// gbufferDefines(), so every layout works in every pass.
#include <optional>
#include <string>
#include <vector>

#include "engine/core/enum_table.hpp"

namespace lp {

enum class GBufferNormalFormat {
    Unpacked,          // RGBA32F xyz (the seeds' default)
    SeedPacked,        // seed 001: RGBA16F (x, y, shininess), z rebuilt >= 0: wrong for z < 0
    SeedPackedSigned,  // the fix: the sign of z in the shininess channel's sign bit
    TwoAngle,          // seed 004: RG32F (phi, cos theta)
    Oct16,             // octahedral, 2 x 8 bits in R16UI
    Oct24,             // octahedral, 2 x 12 bits in R32UI (8 bits spare)
    Oct32,             // octahedral, 2 x 16 bits in R32UI
};
enum class GBufferPositionMode {
    Stored,     // RGBA32F eye-space position target
    Depth,      // rebuilt from the standard D32F depth buffer
    ReversedZ,  // rebuilt from a reversed-Z D32F depth buffer (near 1, far 0, GL_GREATER)
};

// How the G-buffer is made (--gbuffer-mode): rasterising every material attribute, or a visibility
// buffer (depth and a triangle id) resolved into the same targets by a compute pass.
enum class GBufferMode {
    Classic,     // the gbuffer pass writes every target from its fragment shader
    Visibility,  // gbuffer_visibility writes depth + R32UI id; gbuffer_resolve rebuilds the targets
    // Visibility on a hardware rasteriser, classic on a software one (FrameData::softwareRaster):
    // on an H100 the visibility stage costs a third of the classic pass, on llvmpipe 13 times it.
    Auto,
};

struct GBufferSettings {
    GBufferNormalFormat normal = GBufferNormalFormat::Unpacked;
    GBufferPositionMode position = GBufferPositionMode::Stored;
    GBufferMode mode = GBufferMode::Auto;  // the default: visibility on a GPU, classic on a software rasteriser
    bool operator==(const GBufferSettings& o) const {
        return normal == o.normal && position == o.position && mode == o.mode;
    }
    bool operator!=(const GBufferSettings& o) const { return !(*this == o); }
};

inline constexpr EnumName<GBufferNormalFormat> kGBufferNormalFormatNames[] = {
    {GBufferNormalFormat::Unpacked, "unpacked"},   {GBufferNormalFormat::SeedPacked, "seed-packed"},
    {GBufferNormalFormat::SeedPackedSigned, "seed-packed-signed"}, {GBufferNormalFormat::TwoAngle, "two-angle"},
    {GBufferNormalFormat::Oct16, "oct16"},         {GBufferNormalFormat::Oct24, "oct24"},
    {GBufferNormalFormat::Oct32, "oct32"}};
inline constexpr EnumName<GBufferPositionMode> kGBufferPositionModeNames[] = {
    {GBufferPositionMode::Stored, "stored"}, {GBufferPositionMode::Depth, "depth"}, {GBufferPositionMode::ReversedZ, "reversed-z"}};
inline constexpr EnumName<GBufferMode> kGBufferModeNames[] = {  // what --gbuffer-mode takes
    {GBufferMode::Auto, "auto"}, {GBufferMode::Classic, "classic"}, {GBufferMode::Visibility, "visibility"}};

inline const char* gbufferFormatName(GBufferNormalFormat f) { return enumName(kGBufferNormalFormatNames, f); }
inline std::optional<GBufferNormalFormat> parseGBufferFormat(const std::string& name) {
    return parseEnum(kGBufferNormalFormatNames, name);
}
inline std::vector<GBufferNormalFormat> allGBufferFormats() { return enumValues(kGBufferNormalFormatNames); }
inline const char* gbufferPositionName(GBufferPositionMode m) { return enumName(kGBufferPositionModeNames, m); }
inline std::optional<GBufferPositionMode> parseGBufferPosition(const std::string& name) {
    return parseEnum(kGBufferPositionModeNames, name);
}
inline std::vector<GBufferPositionMode> allGBufferPositionModes() { return enumValues(kGBufferPositionModeNames); }
inline const char* gbufferModeName(GBufferMode mode) { return enumName(kGBufferModeNames, mode); }
std::vector<GBufferMode> allGBufferModes();  // the two ways (classic, visibility); not auto
// The way a frame makes its G-buffer and why (the skipped passes' reasons, `lightpass info`).
struct GBufferModeChoice {
    GBufferMode mode = GBufferMode::Classic;  // classic or visibility
    std::string why;                          // starts "--gbuffer-mode <requested>"
};
// `visibilityUnsupported`: why the visibility buffer cannot make this scene's G-buffer on this GPU
// (passes/visibility_resolve_pass: visibilityBufferUnsupported), empty when it can. auto then makes
// the classic G-buffer; an explicit `visibility` throws lp::Error with that reason.
GBufferModeChoice chooseGBufferMode(GBufferMode requested, bool softwareRaster, const std::string& visibilityUnsupported);
std::string gbufferFormatNames();    // "unpacked, seed-packed, ..." for errors and help
std::string gbufferPositionNames();

// The #defines shaders/common/gbuffer_layout.glsl selects its encode/decode with.
std::vector<std::string> gbufferDefines(const GBufferSettings& g);
inline bool shininessInNormalTarget(GBufferNormalFormat f) {
    return f == GBufferNormalFormat::SeedPacked || f == GBufferNormalFormat::SeedPackedSigned;
}
inline bool positionFromDepth(GBufferPositionMode m) { return m != GBufferPositionMode::Stored; }

// Bytes per pixel of the targets the lighting reads: depth, normal, diffuse, specular and, when stored,
// position (not the texcoord target of the texcoords view). The base colour costs the same in every
// layout: kd in 8-bit sRGB (an 8-bit sRGB base colour kept exactly), F0 in RGBA16F or, in the seed
// formats, 8-bit sRGB (passes/gbuffer_pass.hpp).
int gbufferBytesPerPixel(const GBufferSettings& g);

}  // namespace lp
