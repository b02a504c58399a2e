#pragma once
// An environment on the GPU: the equirectangular map converted to a cubemap (RGBA16F, full
// mip chain, the scene's rotation about +Y applied, so it is in world space) and, when IBL needs
// it, the bake: 9 SH coefficients of radiance (CPU, double, from the map), an irradiance cubemap
// and the GGX-prefiltered specular chain (GPU compute). Plus the split-sum DFG LUT. Everything is
// made once per key (map path, rotation, sizes, samples) and kept in memory; with
// EnvironmentSettings::cacheDir the cubes are also written to / read from disk.
#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gl/handles.hpp"
#include "engine/gl/shader.hpp"
#include "engine/render/ibl_lights.hpp"
#include "engine/render/settings.hpp"
#include "engine/scene/scene.hpp"

namespace lp {

struct BakedEnvironment {
    bool hasMap = false;        // false: a uniform environment of the scene's colour
    gl::Texture cube;           // radiance (without the scene's intensity)
    std::string bakeKey;        // empty until baked
    double bakeGpuMs = 0.0;     // GPU time of the last bake (timestamp queries)
    std::array<glm::vec3, 9> sh{};  // SH of radiance
    gl::Texture irradiance;     // E(n), W/m^2
    gl::Texture prefiltered;    // mip m: roughness prefilteredLevelRoughness(m, levels); mip 0 is a copy of a cube mip
    // Sources taken out of the map before the SH, irradiance and prefiltered chain were made (those
    // hold the residual; `cube`, which the sky draws, keeps the original map). Lit analytically.
    std::vector<EnvironmentLight> lights;
    std::vector<std::string> lightSummary;  // describeExtraction's lines, for the log and --explain
};

class EnvironmentCache {
public:
    // The environment of `scene` with its cube made; if `bake`, also its IBL data. Needs GL.
    const BakedEnvironment& get(const Scene& scene, const EnvironmentSettings& settings,
                                const gl::ShaderLibrary& shaders, bool bake);
    // The split-sum DFG LUT of the BRDF with Smith model `masking` (baked again when it changes: the
    // only baked data the masking enters; the cubes, the SH and the extracted lights don't depend on it).
    const gl::Texture& dfgLut(const EnvironmentSettings& settings, SpecularMasking masking,
                              const gl::ShaderLibrary& shaders);
    // Whether get(scene, settings, .., bake) would find everything made already (no GL needed):
    // false in the frame where the environment, the bake settings or (with `bake`) the masking changed.
    bool ready(const Scene& scene, const EnvironmentSettings& settings, SpecularMasking masking, bool bake) const;
    // GPU bytes of every cube and LUT the cache holds (persistent, outside the frame graph's pool).
    size_t gpuBytes() const;
    // Keeps the cubes but forgets every IBL bake, so the next get(.., bake = true) bakes again and
    // lastBakeGpuMs() says what that bake cost (lightpass sweep: each IBL setting's one-off cost).
    void forgetBakes();
    // GPU ms of the last bake run since forgetBakes() (0 when none ran, or it came from the disk cache).
    double lastBakeGpuMs() const { return lastBakeGpuMs_; }

private:
    // The scene's map (or its uniform colour as one), decoded at most once per get(): the cube and
    // the bake both read it, and a large map takes seconds to decode.
    struct DecodedMap {
        const Scene& scene;
        std::optional<ImageF> image;
        const ImageF& get();
        ImageF take();  // the last reader's own copy (the bake removes the extracted lights from it)
    };
    void makeCube(BakedEnvironment& env, const Scene& scene, const EnvironmentSettings& s,
                  const gl::ShaderLibrary& shaders, const std::string& key, DecodedMap& map);
    // Levels 1.. of `cube` from level 0, solid-angle weighted (shaders/ibl_cube_downsample.comp).
    void generateCubeMips(const gl::Texture& cube, const gl::ShaderLibrary& shaders);
    // `cube` level 0 from the equirectangular `map` (rotated about +Y), then its mips. `label` names
    // the map in the warning when it has to be downscaled to fit the GPU.
    void equirectToCube(ImageF map, double rotationDegrees, const gl::Texture& cube, const std::string& label,
                        const gl::ShaderLibrary& shaders);
    void bakeIbl(BakedEnvironment& env, const Scene& scene, const EnvironmentSettings& s,
                 const gl::ShaderLibrary& shaders, const std::string& key, DecodedMap& map);

    std::map<std::string, std::unique_ptr<BakedEnvironment>> environments_;
    gl::Texture dfg_;
    std::string dfgKey_;
    double lastBakeGpuMs_ = 0.0;
    gl::Program toCube_, downsample_, prefilter_, irradiance_, dfgProgram_;
};

// Perceptual roughness of prefiltered mip `level` of `levels`: Filament's mapping, the inverse of
// lod = (levels - 1) r (2 - r) (shaders/common/ibl.glsl prefilteredLodFromRoughness).
float prefilteredLevelRoughness(int level, int levels);

// Mip levels of the environment cubemap under `s` (a full chain of its face size).
int environmentCubeLevels(const EnvironmentSettings& s);

// Throws lp::Error naming the field when the bake settings are unusable (sizes, sample counts).
void validateEnvironmentSettings(const EnvironmentSettings& s);

}  // namespace lp
