// Every enum's table (engine/core/enum_table.hpp) is complete and unambiguous: each enumerator from
// the first to `last` exactly once, each name once, and each name parses back to its value.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>

#include "app/cli.hpp"
#include "engine/post/post_config.hpp"
#include "engine/render/settings.hpp"
#include "frame/light_terms.hpp"

using namespace lp;

namespace {

template <typename E, std::size_t N>
void expectCompleteTable(const EnumName<E> (&table)[N], E last, const char* what) {
    SCOPED_TRACE(what);
    std::vector<int> values;
    std::set<std::string> names;
    for (const EnumName<E>& e : table) {
        values.push_back(int(e.value));
        EXPECT_TRUE(names.insert(e.name).second) << "name '" << e.name << "' twice";
        EXPECT_EQ(parseEnum(table, e.name), e.value) << e.name;
        EXPECT_STREQ(enumName(table, e.value), e.name);
    }
    std::sort(values.begin(), values.end());
    std::vector<int> every(size_t(int(last)) + 1);
    for (size_t i = 0; i < every.size(); ++i) every[i] = int(i);
    EXPECT_EQ(values, every) << "the table must hold each enumerator up to the last exactly once";
    EXPECT_FALSE(parseEnum(table, "no-such-name").has_value());
    EXPECT_FALSE(parseEnum(table, "").has_value());
}

}  // namespace

TEST(EnumTables, EveryTableHoldsEachValueOnceUnderOneName) {
    expectCompleteTable(kBrdfNames, Brdf::BlinnPhong, "brdf");
    expectCompleteTable(kSpecularMaskingNames, SpecularMasking::Separable, "specular masking");
    expectCompleteTable(ShadowSettings::kFilterNames, ShadowSettings::Filter::Poisson, "shadow filter");
    expectCompleteTable(ShadowSettings::kRasterNames, ShadowSettings::Raster::Auto, "shadow raster");
    expectCompleteTable(ShadowSettings::kConservativeRasterNames, ShadowSettings::ConservativeRaster::GeometryShader,
                        "conservative raster");
    expectCompleteTable(kLocalLightMethodNames, LocalLightMethod::Clustered, "local light method");
    expectCompleteTable(kClusteredKernelNames, ClusteredKernel::Tiles, "clustered kernel");
    expectCompleteTable(kToneMapNames, ToneMapOperator::AcesLegacy, "tone map");
    expectCompleteTable(kIrradianceSourceNames, IrradianceSource::Cubemap, "irradiance source");
    expectCompleteTable(kIblSpecularNames, IblSpecular::Sampled, "IBL specular");
    expectCompleteTable(kAoResolutionNames, AoResolution::Half, "AO resolution");
    expectCompleteTable(PostSettings::kBloomMethodNames, PostSettings::BloomMethod::MipChain, "bloom method (setting)");
    expectCompleteTable(post::kBloomMethodNames, post::BloomMethod::MipChain, "bloom method (post)");
    expectCompleteTable(PostSettings::kBackendNames, PostSettings::Backend::Glsl, "post backend");
    expectCompleteTable(PostSettings::kCudaInteropNames, PostSettings::CudaInterop::Map, "CUDA interop");
    expectCompleteTable(kAntiAliasingNames, AntiAliasing::Ssaa, "anti-aliasing");
    expectCompleteTable(kGBufferNormalFormatNames, GBufferNormalFormat::Oct32, "G-buffer normal format");
    expectCompleteTable(kGBufferPositionModeNames, GBufferPositionMode::ReversedZ, "G-buffer position");
    expectCompleteTable(kGBufferModeNames, GBufferMode::Auto, "G-buffer mode");
    expectCompleteTable(kRenderPathNames, RenderPath::PathTraced, "render path");
    expectCompleteTable(kSkinningModeNames, SkinningMode::Cpu, "skinning");
    expectCompleteTable(kViewNames, DebugView::TermClearcoat, "view");
    expectCompleteTable(app::kSweepReferenceNames, app::SweepReference::PathTraced, "sweep reference");
    expectCompleteTable(kLightTermNames, LightTerm::LocalLights, "light term");
}

TEST(EnumTables, CameraViewsAreEveryViewButTheShadowMapAndOverlays) {
    std::vector<DebugView> expected;
    for (DebugView v : everyView())
        if (v != DebugView::ShadowMap && !isLocalLightView(v)) expected.push_back(v);
    EXPECT_EQ(allViews(), expected);
    EXPECT_EQ(everyView().size(), allViews().size() + 1 + localLightViews().size());
}

TEST(EnumTables, NameListIsTheTableInOrder) {
    EXPECT_EQ(enumNameList(kAntiAliasingNames), "off, fxaa, taa, ssaa");
    EXPECT_EQ(enumValues(kAoResolutionNames), (std::vector<AoResolution>{AoResolution::Half, AoResolution::Full}));
}
