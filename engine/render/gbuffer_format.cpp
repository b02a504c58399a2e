#include "engine/render/gbuffer_format.hpp"

#include "engine/core/error.hpp"

namespace lp {

std::vector<GBufferMode> allGBufferModes() { return {GBufferMode::Classic, GBufferMode::Visibility}; }

GBufferModeChoice chooseGBufferMode(GBufferMode requested, bool softwareRaster, const std::string& visibilityUnsupported) {
    switch (requested) {
        case GBufferMode::Classic: return {GBufferMode::Classic, "--gbuffer-mode classic (visibility buffer off)"};
        case GBufferMode::Visibility:
            if (!visibilityUnsupported.empty())
                throw Error("--gbuffer-mode visibility: " + visibilityUnsupported +
                            " (--gbuffer-mode classic or auto make the classic G-buffer)");
            return {GBufferMode::Visibility, "--gbuffer-mode visibility"};
        default: break;
    }
    // Measured: on an H100 the visibility stage costs a third of the classic pass (2.58 against 7.03
    // ms at 4K on the gallery); on llvmpipe its resolve costs 13x the classic raster.
    if (softwareRaster)
        return {GBufferMode::Classic, "--gbuffer-mode auto: classic on a software rasteriser (or without a GPU), "
                                      "where the visibility buffer's resolve costs 13x the classic raster"};
    if (!visibilityUnsupported.empty())
        return {GBufferMode::Classic, "--gbuffer-mode auto: classic, the visibility buffer cannot make this scene's "
                                      "G-buffer: " + visibilityUnsupported};
    return {GBufferMode::Visibility, "--gbuffer-mode auto: visibility on a GPU rasteriser, where the visibility "
                                     "buffer costs a third of the classic G-buffer pass"};
}

std::string gbufferFormatNames() { return enumNameList(kGBufferNormalFormatNames); }

std::string gbufferPositionNames() { return enumNameList(kGBufferPositionModeNames); }

std::vector<std::string> gbufferDefines(const GBufferSettings& g) {
    std::vector<std::string> d;
    switch (g.normal) {
        case GBufferNormalFormat::Unpacked: d.push_back("LP_GBUFFER_NORMAL_UNPACKED"); break;
        case GBufferNormalFormat::SeedPacked: d.push_back("LP_GBUFFER_NORMAL_SEED_PACKED"); break;
        case GBufferNormalFormat::SeedPackedSigned: d.push_back("LP_GBUFFER_NORMAL_SEED_PACKED_SIGNED"); break;
        case GBufferNormalFormat::TwoAngle: d.push_back("LP_GBUFFER_NORMAL_TWO_ANGLE"); break;
        case GBufferNormalFormat::Oct16: d.push_back("LP_GBUFFER_NORMAL_OCT 16"); break;
        case GBufferNormalFormat::Oct24: d.push_back("LP_GBUFFER_NORMAL_OCT 24"); break;
        case GBufferNormalFormat::Oct32: d.push_back("LP_GBUFFER_NORMAL_OCT 32"); break;
    }
    switch (g.position) {
        case GBufferPositionMode::Stored: d.push_back("LP_GBUFFER_POSITION_STORED"); break;
        case GBufferPositionMode::Depth: d.push_back("LP_GBUFFER_POSITION_DEPTH"); break;
        case GBufferPositionMode::ReversedZ: d.push_back("LP_GBUFFER_POSITION_REVERSED_Z"); break;
    }
    return d;
}

int gbufferBytesPerPixel(const GBufferSettings& g) {
    int normal = 16;
    switch (g.normal) {
        case GBufferNormalFormat::Unpacked: normal = 16; break;            // RGBA32F
        case GBufferNormalFormat::SeedPacked:
        case GBufferNormalFormat::SeedPackedSigned: normal = 8; break;     // RGBA16F
        case GBufferNormalFormat::TwoAngle: normal = 8; break;             // RG32F
        case GBufferNormalFormat::Oct16: normal = 2; break;                // R16UI
        case GBufferNormalFormat::Oct24:
        case GBufferNormalFormat::Oct32: normal = 4; break;                // R32UI
    }
    const int specular = shininessInNormalTarget(g.normal) ? 4 : 8;  // SRGB8_A8 F0, or RGBA16F F0 + shininess
    const int position = positionFromDepth(g.position) ? 0 : 16;     // RGBA32F
    return 4 /* D32F */ + normal + 4 /* SRGB8_A8 diffuse */ + specular + position;
}

}  // namespace lp
