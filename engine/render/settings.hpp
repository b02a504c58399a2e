#pragma once
// What the user chose for a frame (CLI flags, keys, the viewer panel): independent of the scene.
// The defaults here are the knobs' defaults: frame/knobs.cpp's table gives each user-facing field its
// flag, range, help and panel widget, and reads the default from RenderSettings{}.
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "engine/core/enum_table.hpp"
#include "engine/render/gbuffer_format.hpp"

namespace lp {

enum class DebugView {
    Final, Depth, Normals, Diffuse, Position, Shininess, Specular, Texcoords, Lighting,
    Environment, Irradiance, Prefiltered, Dfg,  // environment views (passes/ibl_pass)
    ShadowMap,  // light-space depth of light settings.shadows.debugLight's shadow map
    LightRanges, LightsPerTile, LightsPerCluster,  // overlays on the final image (local_light_pass)
    WorldPosition, EyeVector, DepthFitted, Tangent,  // more G-buffer views (seed 003; depth over the scene's range)
    InvalidPixels, ExposureEv,  // the HDR buffer inspected (passes/hdr_view_pass): NaN/Inf, EV false colour
    Velocity,  // gbuffer.velocity: screen-space motion as hue (direction) and brightness (length)
    Ao,  // the ambient-occlusion target (passes/ambient_occlusion_pass)
    // The glTF material's inputs as the material evaluation of either G-buffer mode reads them
    // (gbuffer.material_input, written only in these views); emissive: the emitted radiance alone (HDR).
    BaseColor, Metallic, Roughness, Occlusion, Emissive,
    TermDiffuse, TermSpecular,  // the lit frame with one BRDF term alone (every light, every path)
    TermClearcoat  // ... KHR_materials_clearcoat's layer alone ("clearcoat")
};
// overlay views (not in allViews(): they are the final image with the local lights'
// bounds or per-tile light counts drawn over it).
std::vector<DebugView> localLightViews();
bool isLocalLightView(DebugView view);
// base-color, metallic, roughness, occlusion, emissive (the viewer's `m` key cycles through them).
std::vector<DebugView> materialInputViews();
// term-diffuse, term-specular, clearcoat (the viewer's `t` key cycles through them).
std::vector<DebugView> termViews();
// The view after `view` in `cycle` (the first when `view` is not in it, Final after the last).
DebugView nextViewInCycle(const std::vector<DebugView>& cycle, DebugView view);
// What the lit frame leaves out in `view`, as LP_HIDE_* bits (shaders/common/brdf.glsl: 1 the
// diffuse term, 2 the specular term, 4 emission, 8 the clearcoat layer): term-diffuse hides 2 | 4 | 8,
// term-specular 1 | 4 | 8, clearcoat 1 | 2 | 4, emissive 1 | 2 | 8; every other view 0. The four term
// views add up to the final frame's lit surfaces.
int hiddenShadingTerms(DebugView view);
constexpr int kHideDiffuse = 1, kHideSpecular = 2, kHideEmission = 4, kHideClearcoat = 8;  // = LP_HIDE_*
// The input gbuffer.material_input holds in `view`, as LP_MATERIAL_INPUT_* (shaders/common/material.glsl:
// 1 base colour, 2 metallic, 3 roughness, 4 occlusion); 0 in every other view.
int materialInputShown(DebugView view);
// Views of the lit frame made of some of its terms (term-*, emissive): no sky, no transparent pass.
bool isShadingTermView(DebugView view);

// The BRDF of the light passes (--brdf). GGX (the default): glTF 2.0's metallic-roughness BRDF
// (Appendix B: GGX D, height-correlated Smith, Schlick Fresnel, the dielectric's diffuse weighted by
// 1 - F) for every material, MTL ones as a dielectric with F0 = Ks and alpha from Ns. Blinn-Phong:
// the seeds' energy-normalised Blinn-Phong, Kd / pi + Ks (n + 8) / (8 pi) (N.H)^n, for the analytic
// lights (IBL stays GGX's split sum).
enum class Brdf { Ggx = 0, BlinnPhong = 1 };  // = LP_BRDF_* (shaders/common/brdf.glsl)
inline constexpr EnumName<Brdf> kBrdfNames[] = {{Brdf::Ggx, "ggx"}, {Brdf::BlinnPhong, "blinn-phong"}};
inline const char* brdfName(Brdf brdf) { return enumName(kBrdfNames, brdf); }
inline std::optional<Brdf> parseBrdf(const std::string& name) { return parseEnum(kBrdfNames, name); }

// GGX's Smith masking-shadowing term G2 (--specular-masking), everywhere the BRDF is evaluated or
// integrated (suns, local lights, extracted IBL lights, the DFG LUT, the sampled specular IBL).
// Height-correlated (the default): 1 / (1 + Lambda(V) + Lambda(L)) (Heitz 2014), the glTF
// specification's V_SmithGGXCorrelated, Filament's and Unreal's form. Separable: G1(V) G1(L), the
// form of Mitsuba's built-in roughconductor/roughplastic, up to 5% darker on rough spheres.
enum class SpecularMasking { HeightCorrelated = 0, Separable = 1 };  // = LP_SPECULAR_MASKING_* (brdf.glsl)
inline constexpr EnumName<SpecularMasking> kSpecularMaskingNames[] = {{SpecularMasking::HeightCorrelated, "height-correlated"},
                                                                      {SpecularMasking::Separable, "separable"}};
inline const char* specularMaskingName(SpecularMasking m) { return enumName(kSpecularMaskingNames, m); }

// How opaque surfaces are lit (--render-path): deferred (G-buffer, then the light passes) or
// forward+ (a depth pre-pass, then one forward pass shading each fragment from the clustered light
// lists). Transparent surfaces are drawn forward in both.
// pathtraced: the reference path tracer (passes/path_trace_pass, docs/path-tracer.md) makes the HDR
// frame instead of the raster passes; the post effects, exposure and tone map are the same.
enum class RenderPath { Deferred, ForwardPlus, PathTraced };
inline constexpr EnumName<RenderPath> kRenderPathNames[] = {
    {RenderPath::Deferred, "deferred"}, {RenderPath::ForwardPlus, "forward+"}, {RenderPath::PathTraced, "pathtraced"}};
inline const char* renderPathName(RenderPath path) { return enumName(kRenderPathNames, path); }

// --skinning: where an animated glTF model's vertices are posed each frame (skins, morph targets,
// animated nodes): by the skinning compute pass on the GPU, or on the CPU and uploaded (the
// reference the GPU pass is tested against). docs/motion.md, "Skinning on the GPU".
enum class SkinningMode { Gpu, Cpu };
inline constexpr EnumName<SkinningMode> kSkinningModeNames[] = {{SkinningMode::Gpu, "gpu"}, {SkinningMode::Cpu, "cpu"}};
inline const char* skinningModeName(SkinningMode mode) { return enumName(kSkinningModeNames, mode); }

// Every view --view accepts, in the order --help and the panel list them: the camera's views, then
// the shadow map (a light's depth, needing a shadow-casting light) and the local-light overlays.
inline constexpr EnumName<DebugView> kViewNames[] = {
    {DebugView::Final, "final"},
    {DebugView::Depth, "depth"},
    {DebugView::Normals, "normals"},
    {DebugView::Diffuse, "diffuse"},
    {DebugView::Position, "position"},
    {DebugView::Shininess, "shininess"},
    {DebugView::Specular, "specular"},
    {DebugView::Texcoords, "texcoords"},
    {DebugView::Lighting, "lighting"},
    {DebugView::Environment, "environment"},
    {DebugView::Irradiance, "irradiance"},
    {DebugView::Prefiltered, "prefiltered"},
    {DebugView::Dfg, "dfg"},
    {DebugView::WorldPosition, "world-position"},
    {DebugView::EyeVector, "eye-vector"},
    {DebugView::DepthFitted, "depth-fitted"},
    {DebugView::Tangent, "tangent"},
    {DebugView::InvalidPixels, "invalid-pixels"},
    {DebugView::ExposureEv, "exposure-ev"},
    {DebugView::Velocity, "velocity"},
    {DebugView::Ao, "ao"},
    {DebugView::BaseColor, "base-color"},
    {DebugView::Metallic, "metallic"},
    {DebugView::Roughness, "roughness"},
    {DebugView::Occlusion, "occlusion"},
    {DebugView::Emissive, "emissive"},
    {DebugView::TermDiffuse, "term-diffuse"},
    {DebugView::TermSpecular, "term-specular"},
    {DebugView::TermClearcoat, "clearcoat"},
    {DebugView::ShadowMap, "shadowmap"},
    {DebugView::LightRanges, "light-ranges"},
    {DebugView::LightsPerTile, "lights-per-tile"},
    {DebugView::LightsPerCluster, "lights-per-cluster"},
};
inline const char* viewName(DebugView view) { return enumName(kViewNames, view); }
inline std::optional<DebugView> parseView(const std::string& name) { return parseEnum(kViewNames, name); }
inline std::vector<DebugView> everyView() { return enumValues(kViewNames); }
std::vector<DebugView> allViews();  // the camera's views: everyView() without the shadow map and overlays

// Each feature area owns one of these structs (and only its own fields).
struct ShadowSettings {         // directional-light shadow maps (passes/shadow_map_pass)
    enum class Filter { Off, Pcf3x3, Pcf5x5, Poisson };
    bool enabled = true;
    int size = 2048;            // texels per side of one cascade's square tile
    int cascades = 4;           // 1..4, split by the practical log/linear scheme
    float splitLambda = 0.75f;  // 0: linear splits, 1: logarithmic
    Filter filter = Filter::Pcf3x3;
    float depthBias = 0.5f;     // constant receiver bias, in shadow texels of depth
    float slopeBias = 1.0f;     // glPolygonOffset factor of the depth pass
    float normalBias = 1.0f;    // receiver offset along its normal, in shadow texels (scaled by 1 - N.L)
    int debugLight = 0;         // the shadowmap view shows this directional light's map
    bool cullCasters = true;    // each cascade draws only the caster clusters that can reach its tile
    // Keep each light's atlas across frames and redraw a cascade's tile only when what it would hold
    // changed (its light matrix, the casters, the raster or slope bias); passes/shadow_map_pass.hpp.
    bool cache = true;
    // With the cache on: a cascade whose square only moved by whole texels (same size, light and
    // depth range, casters) keeps the part of its old tile the new square overlaps, moved by that
    // many texels, and redraws only the strips it newly covers (passes/shadow_map_pass.hpp).
    // On by default: on the H100 it lowers the mean and the median (bench/results/shadows/2026-11-24_cascades-moving-camera).
    bool scroll = true;
    // A cascade's square keeps last frame's size while that still holds its slice and is at most
    // 2^(1/4) larger than needed (engine/render/shadows.hpp): fewer whole redraws on a zooming or
    // moving camera, up to 19% less resolution while held.
    bool sizeHold = false;
    // With the cache on: at most this many quarter tiles of resized squares (a scroll counts as one)
    // are drawn per frame, all suns together (0: no limit, every resized square drawn whole at once). A cascade whose new
    // square is not drawn yet keeps serving from its previous square (still exact for that square);
    // where that no longer covers a pixel, the next cascade shades it (passes/shadow_map_pass.hpp).
    int redrawBudget = 2;
    // Room each cascade's square leaves for the camera to move in, as a fraction of its side: the
    // square is that much larger than its slice needs and its origin moves in steps of that much (at
    // least one texel), so a moving camera redraws it less often (engine/render/shadows.hpp).
    float originStep = 0.0625f;
    // How the sun cascades rasterise casters: conservative (grown by half a texel, nearest depth over
    // the texel for faces away from the light: no leak along closed creases, but gl_FragDepth turns
    // early depth testing off), plain (hardware depth at texel centres plus polygon offset), or split
    // (faces towards the light plain with early depth testing, faces away from it conservative), or
    // compute (plain's depths and coverage from a compute rasteriser, atomicMin into an R32UI image;
    // triangles wider or taller than kComputeRasterMaxTexels (passes/shadow_map_pass.hpp) go to the
    // hardware plain path).
    // auto: the fastest of those four on this GPU (measured once, cached; passes/shadow_map_pass.hpp).
    enum class Raster { Conservative, Plain, Split, Compute, Auto };
    Raster raster = Raster::Conservative;
    static constexpr EnumName<Raster> kRasterNames[] = {{Raster::Conservative, "conservative"}, {Raster::Plain, "plain"},
                                                        {Raster::Split, "split"},               {Raster::Compute, "compute"},
                                                        {Raster::Auto, "auto"}};
    static const char* rasterName(Raster r) { return enumName(kRasterNames, r); }

    // How conservative and split grow their casters: hardware (GL_NV_conservative_raster, the nearest
    // depth over the texel from the triangle's depth plane in the fragment shader, needs
    // GL_NV_fragment_shader_barycentric for its vertices; no geometry shader), geometry-shader
    // (shadow_depth.geom, every GPU), or auto: hardware where the GPU has both extensions. hardware
    // on a GPU without them falls back to the geometry shader with a warning.
    enum class ConservativeRaster { Auto, Hardware, GeometryShader };
    ConservativeRaster conservativeRaster = ConservativeRaster::Auto;
    static constexpr EnumName<ConservativeRaster> kConservativeRasterNames[] = {
        {ConservativeRaster::Auto, "auto"}, {ConservativeRaster::Hardware, "hardware"},
        {ConservativeRaster::GeometryShader, "geometry-shader"}};
    static const char* conservativeRasterName(ConservativeRaster c) { return enumName(kConservativeRasterNames, c); }

    static constexpr EnumName<Filter> kFilterNames[] = {
        {Filter::Off, "off"}, {Filter::Pcf3x3, "3x3"}, {Filter::Pcf5x5, "5x5"}, {Filter::Poisson, "poisson"}};
    static const char* filterName(Filter f) { return enumName(kFilterNames, f); }
    static std::optional<Filter> parseFilter(const std::string& name) { return parseEnum(kFilterNames, name); }
};
// how local lights (points and spots) are drawn; all five give the same image (see README).
enum class LocalLightMethod { Fullscreen, Scissor, Volumes, Tiled, Clustered };
inline constexpr EnumName<LocalLightMethod> kLocalLightMethodNames[] = {
    {LocalLightMethod::Fullscreen, "fullscreen"}, {LocalLightMethod::Scissor, "scissor"},
    {LocalLightMethod::Volumes, "volumes"},       {LocalLightMethod::Tiled, "tiled"},
    {LocalLightMethod::Clustered, "clustered"}};
inline const char* localLightMethodName(LocalLightMethod m) { return enumName(kLocalLightMethodNames, m); }
inline std::optional<LocalLightMethod> parseLocalLightMethod(const std::string& name) {
    return parseEnum(kLocalLightMethodNames, name);
}
inline std::vector<LocalLightMethod> allLocalLightMethods() { return enumValues(kLocalLightMethodNames); }
// Which kernel the clustered method shades with (16-pixel froxel tiles; other sizes always froxels):
// auto races the two per view (engine/render/kernel_race.hpp) and takes the faster; froxels is the
// clustered kernel, tiles the tiled kernel on the same tiles without slices. The same image.
enum class ClusteredKernel { Auto, Froxels, Tiles };
inline constexpr EnumName<ClusteredKernel> kClusteredKernelNames[] = {
    {ClusteredKernel::Auto, "auto"}, {ClusteredKernel::Froxels, "froxels"}, {ClusteredKernel::Tiles, "tiles"}};
inline const char* clusteredKernelName(ClusteredKernel k) { return enumName(kClusteredKernelNames, k); }
struct LocalLightSettings {     // local lights: ranged point lights and spots
    bool enabled = true;
    LocalLightMethod method = LocalLightMethod::Tiled;
    bool scissor = true;        // scissor method: off draws every light full screen ('x' toggles)
    int lightCount = -1;        // -1: the scene's lights; N: the first N, plus generated demo lights up to N
    std::optional<bool> globes; // small flat-lit spheres at the lights; unset: the scene's lightGlobes
    bool specular = true;       // local lights add a specular term
    bool specularOutsideRange = false;  // diffuse limited by range, specular (1/d^2 only) not
    float rangeScale = 1.0f;    // --light-range-scale: each light's range x this (< 1 cuts lights short; a sweep knob)
    int clusterSize = 16;       // clustered: froxel tile side in pixels (the fused pass's work group)
    int clusterSlices = 24;     // clustered: exponential depth slices between the near and far planes
    ClusteredKernel clusteredKernel = ClusteredKernel::Auto;  // clustered: which kernel shades (above)
    int clusterSlice = -1;      // lights-per-cluster view: this slice, -1 the most over all slices
};
// Tone map operators (shaders/common/tonemap.glsl's applyToneMap numbers them in this order). Aces is
// Filament's ACES (the RRT + ODT fit); AcesLegacy the Narkowicz fit without its 0.6 input scale.
enum class ToneMapOperator { Lightpass, Aces, PbrNeutral, Agx, AcesLegacy };
inline constexpr EnumName<ToneMapOperator> kToneMapNames[] = {  // in --tonemap's order
    {ToneMapOperator::Lightpass, "lightpass"},    {ToneMapOperator::Aces, "aces"}, {ToneMapOperator::AcesLegacy, "aces-legacy"},
    {ToneMapOperator::PbrNeutral, "pbr-neutral"}, {ToneMapOperator::Agx, "agx"}};
inline const char* toneMapName(ToneMapOperator op) { return enumName(kToneMapNames, op); }
inline std::optional<ToneMapOperator> parseToneMap(const std::string& name) { return parseEnum(kToneMapNames, name); }
inline std::vector<ToneMapOperator> allToneMapOperators() { return enumValues(kToneMapNames); }
enum class IrradianceSource { SphericalHarmonics, Cubemap };
inline constexpr EnumName<IrradianceSource> kIrradianceSourceNames[] = {{IrradianceSource::SphericalHarmonics, "sh"},
                                                                        {IrradianceSource::Cubemap, "cubemap"}};
// Specular IBL: the split sum (one prefiltered lookup x the DFG LUT), or per-pixel GGX samples of the
// prefiltered chain that follow the lobe's shape (shaders/common/ibl_sampled.glsl).
enum class IblSpecular { SplitSum, Sampled };
inline constexpr EnumName<IblSpecular> kIblSpecularNames[] = {{IblSpecular::SplitSum, "split-sum"},
                                                              {IblSpecular::Sampled, "sampled"}};
inline const char* iblSpecularName(IblSpecular m) { return enumName(kIblSpecularNames, m); }
struct EnvironmentSettings {    // environment, skybox, image-based lighting, tone map operator
    // false: analytic lights + constant ambient; true: + IBL. Unset: the scene's environment.ibl.
    std::optional<bool> ibl;
    int cubeSize = 512;         // face size of the environment cubemap (full mip chain)
    int specularSize = 256;     // face size of the prefiltered specular cube (<= cubeSize)
    int specularLevels = 6;     // prefiltered mips: level m holds roughness m / (levels - 1)
    int specularSamples = 1024;  // GGX importance samples per prefiltered texel (bench/mitsuba: 256 left rough spheres 9-14% bright under a 50,000 lamp)
    int irradianceSize = 32;    // face size of the irradiance cubemap
    int irradianceSamples = 4096;  // cosine-weighted samples per irradiance texel (512 read 3% high under a 50,000 lamp)
    int dfgSize = 128;          // split-sum DFG LUT is dfgSize x dfgSize RG16F
    int dfgSamples = 512;       // GGX samples per LUT texel
    IrradianceSource diffuse = IrradianceSource::SphericalHarmonics;
    IblSpecular specular = IblSpecular::SplitSum;  // bench/results/mitsuba/2026-11-24_ibl-against-mitsuba/sampled_specular.md
    int specularRuntimeSamples = 64;  // per pixel, with IblSpecular::Sampled (fewer: the pattern shows in the error)
    // Small, very bright sources taken out of the map at bake time and lit as directional lights
    // (engine/render/ibl_lights.hpp): at most this many (0: off, <= kMaxEnvironmentLights), regions whose
    // luminance is above extractThreshold times the map's median.
    int extractLights = 4;
    float extractThreshold = 100.0f;
    ToneMapOperator toneMap = ToneMapOperator::Lightpass;
    int debugMip = 0;           // the 'prefiltered' debug view shows this mip
    std::string cacheDir;       // non-empty: baked environments are also cached on disk here
};
// Screen-space ambient occlusion (GTAO, passes/ambient_occlusion_pass): darkens only indirect light
// (IBL diffuse and the constant ambient; IBL specular through specular occlusion), never the suns or
// local lights. The frame builder runs it only where indirect light exists.
enum class AoResolution { Full, Half };
inline constexpr EnumName<AoResolution> kAoResolutionNames[] = {{AoResolution::Half, "half"}, {AoResolution::Full, "full"}};
inline const char* aoResolutionName(AoResolution r) { return enumName(kAoResolutionNames, r); }
struct AoSettings {
    bool enabled = true;        // --ao / --no-ao
    float radius = 1.0f;        // view-space search radius, metres
    int directions = 2;         // slice directions per texel (rotated per texel over an 8x8 tile)
    int steps = 8;              // depth samples per side of each slice
    AoResolution resolution = AoResolution::Half;  // half: computed at half size, depth-aware upsample
    float intensity = 1.0f;     // AO^intensity (1: the physical value)
};
struct PostSettings {           // bloom and toon (engine/post/post_config.hpp resolves them)
    enum class BloomMethod { Separable, MipChain };
    static constexpr EnumName<BloomMethod> kBloomMethodNames[] = {{BloomMethod::Separable, "separable"},
                                                                  {BloomMethod::MipChain, "mip-chain"}};
    enum class Backend { Auto, Cuda, Glsl };  // auto: CUDA on an NVIDIA GL context with a CUDA device
    static constexpr EnumName<Backend> kBackendNames[] = {{Backend::Auto, "auto"}, {Backend::Cuda, "cuda"}, {Backend::Glsl, "glsl"}};
    // Unset: the scene's effects.bloom / effects.toon value.
    std::optional<bool> bloom, toon;
    std::optional<int> bloomKernel;  // 1..101 px
    std::optional<float> bloomThreshold, bloomKnee, bloomStrength;
    BloomMethod bloomMethod = BloomMethod::Separable;
    float bloomHighlight = 1000.0f;  // per-channel ceiling entering the blur
    bool bloomKaris = true;          // mip chain: Karis average on the first downsample
    bool bloomFragmentBlur = false;  // GLSL separable: blur with fragment passes (benchmark)
    bool bloomOnly = false;          // display the bloom buffer alone (seed 001's '8')
    std::optional<int> toonLevels;
    std::optional<float> toonEdge;   // depth-edge threshold
    float toonNormalEdge = 0.5f;     // normal-edge threshold (sin of half the crease angle)
    Backend backend = Backend::Auto;
    // How CUDA reaches the GL textures: external (GL memory objects on CUDA allocations, shared once),
    // map (cudaGraphicsMapResources per use), auto: map (external is experimental: README).
    enum class CudaInterop { Auto, External, Map };
    static constexpr EnumName<CudaInterop> kCudaInteropNames[] = {
        {CudaInterop::Auto, "auto"}, {CudaInterop::External, "external"}, {CudaInterop::Map, "map"}};
    CudaInterop cudaInterop = CudaInterop::Auto;
    bool remeasure = false;  // --post-remeasure: auto measures again instead of reading its cache
};

struct MotionBlurSettings {     // passes/motion_blur_pass (McGuire et al. 2012)
    bool enabled = false;       // --motion-blur
    int samples = 16;           // --motion-blur-samples: gather taps per pixel
    float shutter = 0.5f;       // --motion-blur-shutter: fraction of the frame interval the shutter is open
};

inline constexpr float kMinRenderScale = 0.25f;  // --render-scale's lower bound

// Anti-aliasing (--aa). ssaa renders at --ssaa-scale S times the output size in each axis (S x S
// samples a pixel) and box-filters the HDR image down before the tone map; fxaa filters the
// tone-mapped image; taa blends jittered frames through the motion vectors.
enum class AntiAliasing { Off, Fxaa, Taa, Ssaa };
inline constexpr EnumName<AntiAliasing> kAntiAliasingNames[] = {
    {AntiAliasing::Off, "off"}, {AntiAliasing::Fxaa, "fxaa"}, {AntiAliasing::Taa, "taa"}, {AntiAliasing::Ssaa, "ssaa"}};
inline const char* antiAliasingName(AntiAliasing aa) { return enumName(kAntiAliasingNames, aa); }
inline constexpr int kMaxSsaaScale = 4;
struct AntiAliasSettings {
    // SSAA 2x2 by default: of the methods it alone lowers the error against 4x4 SSAA on a moving
    // camera (bench/results/aa: TAA and FXAA raise it), and a single still frame is already resolved.
    AntiAliasing method = AntiAliasing::Ssaa;
    int ssaaScale = 2;              // --ssaa-scale: samples per axis with --aa ssaa (2..4)
    float taaHistoryWeight = 0.1f;  // --taa-history-weight: the current frame's weight in the TAA blend
    bool dither = true;             // triangular-PDF noise of +-1 LSB before every 8-bit quantisation
};

// The path tracer's sampling (--spp, --bounces, --direct-only, --pixel-centre).
struct PathTraceSettings {
    int samples = 64;         // samples per pixel, accumulated before the frame is shown
    int bounces = 8;          // surface interactions whose scattered light counts (Russian roulette from 3)
    bool directOnly = false;  // one interaction: the lights, the environment and emitters seen from it
    bool pixelCentre = false; // every sample through the pixel's centre (else jittered: box-filtered)
    // --env-sampling: an environment map is sampled by its luminance too (multiple importance
    // sampling with the BRDF), or by the BRDF alone (slower to converge on a small bright lamp).
    bool environmentSampling = true;
    int interactions() const { return directOnly ? 1 : bounces; }
};

struct RenderSettings {
    int width = 1280;
    int height = 720;
    // --render-scale: the G-buffer, lighting and post effects run at round(size x renderScale)
    // (0.25..1) and are upsampled bilinearly to width x height before the tone map. At 1 with --aa ssaa
    // they run at ssaaScale x the size instead; below 1 the render scale is kept and SSAA is not used
    // (supersampled() and internalRenderScale() in frame/frame_builder.hpp).
    float renderScale = 1.0f;
    AntiAliasSettings aa;
    DebugView view = DebugView::Final;
    // --exposure: EV added to the scene's exposure (the metered one, or the scene file's fixed
    // "exposure"); engine/render/exposure.hpp resolves both.
    float exposureEV = 0.0f;
    // --auto-exposure / --no-auto-exposure: the histogram pass meters each frame. Unset: the scene's
    // choice, on unless the scene file fixes an "exposure".
    std::optional<bool> autoExposure;
    Brdf brdf = Brdf::Ggx;  // BRDF of the light passes: glTF 2.0's (GGX) for every material
    SpecularMasking specularMasking = SpecularMasking::HeightCorrelated;  // GGX's G2, lights and IBL alike
    RenderPath renderPath = RenderPath::Deferred;  // --render-path
    SkinningMode skinning = SkinningMode::Gpu;     // --skinning
    PathTraceSettings pathTrace;  // --render-path pathtraced and `lightpass reference`
    bool keepHdr = false;        // keep the HDR buffer as an output (EXR dumps)
    // --all-passes: add every candidate pass even where the scene does not call for it (shadow maps
    // for every sun, local lights with none in view, a colour sky, bloom at strength 0); measuring only.
    bool allPasses = false;
    std::set<std::string> disabledPasses;  // switched off in the UI / --disable-pass
    ShadowSettings shadows;
    LocalLightSettings localLights;
    EnvironmentSettings environment;
    AoSettings ao;
    PostSettings post;
    MotionBlurSettings motionBlur;
    GBufferSettings gbuffer;     // normal format and position mode (--gbuffer, --gbuffer-position)
};

}  // namespace lp
