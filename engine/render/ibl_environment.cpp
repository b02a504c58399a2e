#include "engine/render/ibl_environment.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/core/progress.hpp"
#include "engine/gl/limits.hpp"
#include "engine/gl/state.hpp"
#include "engine/gl/uniforms.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/io/image_io.hpp"
#include "engine/render/ibl_lights.hpp"
#include "engine/render/ibl_sh.hpp"

namespace lp {

namespace fs = std::filesystem;

namespace {

bool isPowerOfTwo(int x) { return x > 0 && (x & (x - 1)) == 0; }

int log2Int(int x) {
    int l = 0;
    while ((1 << (l + 1)) <= x) ++l;
    return l;
}

// A uniform environment is the same at every resolution: bake it small.
EnvironmentSettings effectiveSettings(const EnvironmentSettings& s, bool hasMap) {
    if (hasMap) return s;
    EnvironmentSettings u = s;
    u.cubeSize = std::min(s.cubeSize, 16);
    u.specularSize = std::min(s.specularSize, u.cubeSize);
    u.specularLevels = std::min(s.specularLevels, log2Int(u.specularSize) + 1);
    u.irradianceSize = std::min(s.irradianceSize, 8);
    return u;
}

std::string fmt(double x) {
    char b[32];
    std::snprintf(b, sizeof b, "%.9g", x);
    return b;
}

// Identity of the map file: a changed file (new mtime or size) is a new key.
std::string sourceKey(const Scene& scene) {
    const Environment& e = scene.environment;
    if (e.map.empty())
        return "color:" + fmt(e.color.x) + "," + fmt(e.color.y) + "," + fmt(e.color.z);
    std::error_code ec;
    auto size = fs::file_size(e.map, ec);
    auto time = fs::last_write_time(e.map, ec).time_since_epoch().count();
    return "map:" + fs::absolute(e.map).lexically_normal().string() + "|bytes=" + std::to_string(ec ? 0 : size) +
           "|mtime=" + std::to_string(ec ? 0 : time) + "|rot=" + fmt(e.rotationDegrees);
}

std::string cubeKey(const Scene& scene, const EnvironmentSettings& s) {
    return sourceKey(scene) + "|cube=" + std::to_string(s.cubeSize) + "|mips=solid-angle";
}

std::string bakeKeyOf(const std::string& cube, const EnvironmentSettings& s) {
    return cube + "|spec=" + std::to_string(s.specularSize) + "x" + std::to_string(s.specularLevels) + "x" +
           std::to_string(s.specularSamples) + "|lod=perceptual|irr=" + std::to_string(s.irradianceSize) + "x" +
           std::to_string(s.irradianceSamples) + "|lights=" + std::to_string(s.extractLights) + "@" +
           fmt(s.extractThreshold);
}

uint64_t fnv1a(const std::string& text) {
    uint64_t h = 1469598103934665603ull;
    for (unsigned char c : text) h = (h ^ c) * 1099511628211ull;
    return h;
}

fs::path cacheFile(const std::string& dir, const std::string& kind, const std::string& key) {
    char name[64];
    std::snprintf(name, sizeof name, "%s-%016llx.lpibl", kind.c_str(), static_cast<unsigned long long>(fnv1a(key)));
    return fs::path(dir) / name;
}

size_t levelBytes(const gl::Texture& t, int level) {
    const size_t s = size_t(std::max(t.width >> level, 1));
    return s * s * 6 * 4 * sizeof(uint16_t);
}

// Per extracted light: direction, irradiance, solid angle, angular radius (8 floats) and its texels.
struct StoredLight {
    float values[8];
    int32_t texels;
};

// Cache file: "lightpass-ibl 2\n<key>\n"; with SH (a bake): 9 SH vec3 (float), the count of extracted
// lights (int32) and each light (StoredLight); then each cube's levels as RGBA half.
void saveCache(const fs::path& path, const std::string& key, const std::array<glm::vec3, 9>* sh,
               const std::vector<EnvironmentLight>* lights, const std::vector<const gl::Texture*>& cubes) {
    std::error_code ec;
    fs::create_directories(path.parent_path(), ec);
    if (ec) throw Error(path.parent_path().string() + ": cannot create the IBL cache folder: " + ec.message());
    writeFileAtomically(path, [&](const fs::path& tmp) {
        std::ofstream out(tmp, std::ios::binary);
        out << "lightpass-ibl 2\n" << key << "\n";
        if (sh) out.write(reinterpret_cast<const char*>(sh->data()), sizeof(*sh));
        if (sh) {
            const int32_t count = lights ? int32_t(lights->size()) : 0;
            out.write(reinterpret_cast<const char*>(&count), sizeof count);
            for (int32_t i = 0; i < count; ++i) {
                const EnvironmentLight& l = (*lights)[size_t(i)];
                const StoredLight stored{{l.direction.x, l.direction.y, l.direction.z, l.irradiance.x, l.irradiance.y,
                                          l.irradiance.z, l.solidAngle, l.angularRadius},
                                         l.texels};
                out.write(reinterpret_cast<const char*>(&stored), sizeof stored);
            }
        }
        std::vector<char> data;
        for (const gl::Texture* t : cubes)
            for (int l = 0; l < t->levels; ++l) {
                data.resize(levelBytes(*t, l));
                glGetTextureImage(t->id(), l, GL_RGBA, GL_HALF_FLOAT, GLsizei(data.size()), data.data());
                out.write(data.data(), std::streamsize(data.size()));
            }
        if (!out) throw Error(tmp.string() + ": write failed");
    });
}

// False (and the textures untouched) when the file is absent or not for `key`.
bool loadCache(const fs::path& path, const std::string& key, std::array<glm::vec3, 9>* sh,
               std::vector<EnvironmentLight>* lights, const std::vector<gl::Texture*>& cubes) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    std::string magic, storedKey;
    std::getline(in, magic);
    std::getline(in, storedKey);
    if (magic != "lightpass-ibl 2" || storedKey != key) return false;
    std::array<glm::vec3, 9> shRead{};
    if (sh && !in.read(reinterpret_cast<char*>(shRead.data()), sizeof(shRead))) return false;
    std::vector<EnvironmentLight> lightsRead;
    if (sh) {
        int32_t count = 0;
        if (!in.read(reinterpret_cast<char*>(&count), sizeof count) || count < 0 || count > kMaxEnvironmentLights)
            return false;
        for (int32_t i = 0; i < count; ++i) {
            StoredLight stored{};
            if (!in.read(reinterpret_cast<char*>(&stored), sizeof stored)) return false;
            EnvironmentLight l;
            l.direction = {stored.values[0], stored.values[1], stored.values[2]};
            l.irradiance = {stored.values[3], stored.values[4], stored.values[5]};
            l.solidAngle = stored.values[6];
            l.angularRadius = stored.values[7];
            l.texels = stored.texels;
            lightsRead.push_back(l);
        }
    }
    std::vector<std::vector<char>> levels;
    for (const gl::Texture* t : cubes)
        for (int l = 0; l < t->levels; ++l) {
            levels.emplace_back(levelBytes(*t, l));
            if (!in.read(levels.back().data(), std::streamsize(levels.back().size()))) {
                logWarn(path.string() + ": truncated IBL cache file, baking again");
                return false;
            }
        }
    size_t i = 0;
    for (gl::Texture* t : cubes)
        for (int l = 0; l < t->levels; ++l) {
            const int s = std::max(t->width >> l, 1);
            glTextureSubImage3D(t->id(), l, 0, 0, 0, s, s, 6, GL_RGBA, GL_HALF_FLOAT, levels[i++].data());
        }
    if (sh) *sh = shRead;
    if (lights) *lights = lightsRead;
    return true;
}

void dispatchCube(int size) {
    glDispatchCompute(GLuint((size + 7) / 8), GLuint((size + 7) / 8), 6);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

double secondsSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

ImageF uniformImage(glm::vec3 c) {
    ImageF img;
    img.width = 4;
    img.height = 2;
    for (int i = 0; i < 8; ++i) img.rgba.insert(img.rgba.end(), {c.x, c.y, c.z, 1.0f});
    return img;
}

}  // namespace

int environmentCubeLevels(const EnvironmentSettings& s) { return log2Int(s.cubeSize) + 1; }

float prefilteredLevelRoughness(int level, int levels) {
    if (levels <= 1) return 0.0f;
    const double t = double(level) / double(levels - 1);
    return float(1.0 - std::sqrt(std::max(1.0 - t, 0.0)));
}

void EnvironmentCache::generateCubeMips(const gl::Texture& cube, const gl::ShaderLibrary& shaders) {
    if (!downsample_) downsample_ = shaders.compute("ibl_cube_downsample.comp");
    const GLuint prog = downsample_.id();
    glUseProgram(prog);
    for (int level = 1; level < cube.levels; ++level) {
        const int finer = std::max(cube.width >> (level - 1), 1);
        glProgramUniform1i(prog, gl::Uniforms(&shaders, prog).location("uFinerSize"), finer);
        glBindImageTexture(0, cube.id(), level - 1, GL_TRUE, 0, GL_READ_ONLY, GL_RGBA16F);
        glBindImageTexture(1, cube.id(), level, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        dispatchCube(std::max(finer / 2, 1));
    }
    glUseProgram(0);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA16F);
    glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
}

void validateEnvironmentSettings(const EnvironmentSettings& s) {
    // Each message names the flags (and so the sweep knobs / panel widgets) that hold the values:
    // "specular size 256" said nothing about which flag to change.
    auto need = [](bool ok, const std::string& msg) {
        if (!ok) throw Error("environment settings: " + msg);
    };
    const std::string cube = std::to_string(s.cubeSize), specular = std::to_string(s.specularSize);
    need(isPowerOfTwo(s.cubeSize) && s.cubeSize >= 4 && s.cubeSize <= 4096, "--env-size " + cube + " must be a power of two in [4, 4096]");
    need(isPowerOfTwo(s.specularSize) && s.specularSize >= 4 && s.specularSize <= s.cubeSize,
         "--ibl-specular-size " + specular + " must be a power of two in [4, --env-size " + cube + "]");
    need(s.specularLevels >= 1 && s.specularLevels <= log2Int(s.specularSize) + 1,
         "--ibl-specular-levels " + std::to_string(s.specularLevels) + " must be in [1, " + std::to_string(log2Int(s.specularSize) + 1) +
             "] for --ibl-specular-size " + specular);
    need(s.specularSamples >= 1 && s.specularSamples <= 65536, "--ibl-samples must be in [1, 65536]");
    need(s.irradianceSize >= 1 && s.irradianceSize <= 1024, "--ibl-irradiance-size must be in [1, 1024]");
    need(s.irradianceSamples >= 1 && s.irradianceSamples <= 65536, "--ibl-irradiance-samples must be in [1, 65536]");
    need(s.dfgSize >= 2 && s.dfgSize <= 1024, "--dfg-size must be in [2, 1024]");
    need(s.dfgSamples >= 1 && s.dfgSamples <= 65536, "--dfg-samples must be in [1, 65536]");
    need(s.debugMip >= 0, "--ibl-mip must be >= 0");
    need(s.extractLights >= 0 && s.extractLights <= kMaxEnvironmentLights,
         "--ibl-extract-lights " + std::to_string(s.extractLights) + " must be in [0, " + std::to_string(kMaxEnvironmentLights) + "]");
    need(std::isfinite(s.extractThreshold) && s.extractThreshold >= 1.0f, "--ibl-extract-threshold must be >= 1");
    need(s.specularRuntimeSamples >= 1 && s.specularRuntimeSamples <= 256,
         "--ibl-specular-samples " + std::to_string(s.specularRuntimeSamples) + " must be in [1, 256]");
}

const BakedEnvironment& EnvironmentCache::get(const Scene& scene, const EnvironmentSettings& requested,
                                              const gl::ShaderLibrary& shaders, bool bake) {
    validateEnvironmentSettings(requested);
    const bool hasMap = !scene.environment.map.empty();
    const EnvironmentSettings s = effectiveSettings(requested, hasMap);
    const std::string key = cubeKey(scene, s);
    DecodedMap map{scene, std::nullopt};
    auto it = environments_.find(key);
    if (it == environments_.end()) {
        if (environments_.size() >= 4) environments_.clear();  // bounded: maps are tens of MB each
        auto env = std::make_unique<BakedEnvironment>();
        env->hasMap = hasMap;
        makeCube(*env, scene, s, shaders, key, map);
        it = environments_.emplace(key, std::move(env)).first;
    }
    BakedEnvironment& env = *it->second;
    const std::string bakeKey = bakeKeyOf(key, s);
    if (bake && env.bakeKey != bakeKey) bakeIbl(env, scene, s, shaders, bakeKey, map);
    return env;
}

const ImageF& EnvironmentCache::DecodedMap::get() {
    if (image) return *image;
    if (scene.environment.map.empty()) return image.emplace(uniformImage(scene.environment.color));
    image = loadHdrImage(scene.environment.map);
    // Read as latitude-longitude whatever its shape: a cross, a mirror ball or a square map comes
    // out stretched, which the user should hear about.
    if (image->width != 2 * image->height)
        logWarn(scene.environment.map.string() + ": " + std::to_string(image->width) + "x" + std::to_string(image->height) +
                " is not 2:1; read as an equirectangular (latitude-longitude) map, stretched");
    return *image;
}

ImageF EnvironmentCache::DecodedMap::take() {
    get();
    ImageF out = std::move(*image);
    image.reset();
    return out;
}

namespace {
std::string dfgKeyOf(const EnvironmentSettings& s, SpecularMasking masking) {
    return std::to_string(s.dfgSize) + "x" + std::to_string(s.dfgSamples) + "|" + specularMaskingName(masking);
}
}  // namespace

bool EnvironmentCache::ready(const Scene& scene, const EnvironmentSettings& requested, SpecularMasking masking,
                             bool bake) const {
    const EnvironmentSettings s = effectiveSettings(requested, !scene.environment.map.empty());
    const std::string key = cubeKey(scene, s);
    auto it = environments_.find(key);
    if (it == environments_.end()) return false;
    return !bake || (it->second->bakeKey == bakeKeyOf(key, s) && dfg_ && dfgKey_ == dfgKeyOf(s, masking));
}

size_t EnvironmentCache::gpuBytes() const {
    auto bytes = [](const gl::Texture& t) -> size_t {
        if (!t) return 0;
        const size_t faces = t.target == GL_TEXTURE_CUBE_MAP ? 6 : 1;
        return faces * fg::TextureDesc{t.width, t.height, t.format, t.levels}.bytes();
    };
    size_t total = bytes(dfg_);
    for (const auto& [key, env] : environments_)
        total += bytes(env->cube) + bytes(env->irradiance) + bytes(env->prefiltered);
    return total;
}

void EnvironmentCache::equirectToCube(ImageF map, double rotationDegrees, const gl::Texture& cube,
                                      const std::string& label, const gl::ShaderLibrary& shaders) {
    // Over the GPU's texture limits: halved until it fits, with a warning (docs/bad-input.md).
    if (const gl::TextureFit fit = gl::fitTexture(GL_RGBA32F, map.width, map.height); fit.halvings > 0) {
        const int w = map.width, h = map.height;
        map = downscaleToFit(map, std::max(w, h) >> fit.halvings);
        logWarn(label + ": " + std::to_string(w) + "x" + std::to_string(h) + " is " + fit.reason +
                "; downscaled to " + std::to_string(map.width) + "x" + std::to_string(map.height));
    }
    gl::Texture equirect = gl::makeTexture2D(GL_RGBA32F, map.width, map.height, 1, "ibl.equirect");
    glTextureSubImage2D(equirect.id(), 0, 0, 0, map.width, map.height, GL_RGBA, GL_FLOAT, map.rgba.data());
    glTextureParameteri(equirect.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(equirect.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(equirect.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(equirect.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    if (!toCube_) toCube_ = shaders.compute("ibl_equirect_to_cube.comp");
    const GLuint prog = toCube_.id();
    // Map texels per cube texel at the equator, times 2: enough taps that poles and small faces
    // average their footprint instead of aliasing.
    const double ratio = double(map.width) / (3.14159265358979 * cube.width);
    const int taps = std::clamp(int(std::ceil(2.0 * ratio)), 2, 8);
    glProgramUniform1i(prog, gl::Uniforms(&shaders, prog).location("uSize"), cube.width);
    glProgramUniform1i(prog, gl::Uniforms(&shaders, prog).location("uTaps"), taps);
    glProgramUniform1f(prog, gl::Uniforms(&shaders, prog).location("uRotation"), float(rotationDegrees * 3.14159265358979 / 180.0));
    glBindTextureUnit(0, equirect.id());
    glBindImageTexture(0, cube.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glUseProgram(prog);
    dispatchCube(cube.width);
    glUseProgram(0);
    glBindTextureUnit(0, 0);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    generateCubeMips(cube, shaders);
    gl::checkErrors("converting the environment map to a cubemap");
}

void EnvironmentCache::makeCube(BakedEnvironment& env, const Scene& scene, const EnvironmentSettings& s,
                                const gl::ShaderLibrary& shaders, const std::string& key, DecodedMap& map) {
    const int levels = environmentCubeLevels(s);
    env.cube = gl::makeTextureCube(GL_RGBA16F, s.cubeSize, levels, "ibl.environment");
    const bool useDisk = env.hasMap && !s.cacheDir.empty();
    const fs::path file = useDisk ? cacheFile(s.cacheDir, "cube", key) : fs::path();
    if (useDisk && loadCache(file, key, nullptr, nullptr, {&env.cube})) {
        logInfo("ibl: environment cube read from " + file.string());
        return;
    }
    const auto t0 = std::chrono::steady_clock::now();
    equirectToCube(map.get(), scene.environment.rotationDegrees, env.cube, scene.environment.map.string(), shaders);
    if (env.hasMap) {
        glFinish();
        logInfo("ibl: " + scene.environment.map.string() + " -> cubemap " + std::to_string(s.cubeSize) + "^2 x 6 (" +
                std::to_string(levels) + " mips) in " + fmt(std::round(secondsSince(t0) * 1000.0)) + " ms");
    }
    if (useDisk) saveCache(file, key, nullptr, nullptr, {&env.cube});
}

void EnvironmentCache::bakeIbl(BakedEnvironment& env, const Scene& scene, const EnvironmentSettings& s,
                               const gl::ShaderLibrary& shaders, const std::string& key, DecodedMap& decoded) {
    env.prefiltered = gl::makeTextureCube(GL_RGBA16F, s.specularSize, s.specularLevels, "ibl.prefiltered");
    env.irradiance = gl::makeTextureCube(GL_RGBA16F, s.irradianceSize, 1, "ibl.irradiance");
    const bool useDisk = env.hasMap && !s.cacheDir.empty();
    const fs::path file = useDisk ? cacheFile(s.cacheDir, "bake", key) : fs::path();
    if (useDisk && loadCache(file, key, &env.sh, &env.lights, {&env.prefiltered, &env.irradiance})) {
        env.bakeKey = key;
        LightExtraction stored;
        stored.lights = env.lights;
        env.lightSummary = describeExtraction(stored, s.extractLights);
        logInfo("ibl: baked environment read from " + file.string());
        return;
    }
    const auto t0 = std::chrono::steady_clock::now();
    const std::string what = env.hasMap ? scene.environment.map.string() : std::string("uniform environment");
    // Steps: light extraction, SH, the irradiance cube, each prefiltered mip past the copied mip 0.
    // On stderr as a progress bar (lines in a log) when the bake takes seconds; each step's detail
    // with -v. A uniform environment bakes in milliseconds and shows nothing.
    ProgressStyle style = stderrProgressStyle();
    style.quiet = style.quiet || !env.hasMap;
    ProgressReporter bakeProgress("ibl: baking " + what, size_t(2 + s.specularLevels), std::cerr, style, steadySeconds);
    auto progress = [&](const std::string& step) {
        if (env.hasMap) logDebug("ibl: " + what + ": " + step);
        bakeProgress.step(step);
    };

    // Diffuse SH: on the CPU, in double, from the equirectangular map (not from the clamped cube).
    ImageF map = decoded.take();
    // The small, very bright sources leave the map here: everything below is made from the residual.
    env.lights.clear();
    env.lightSummary.clear();
    if (env.hasMap) {
        const LightExtraction extraction =
            extractEnvironmentLights(map, scene.environment.rotationDegrees, s.extractLights, s.extractThreshold);
        env.lights = extraction.lights;
        env.lightSummary = describeExtraction(extraction, s.extractLights);
        for (const std::string& line : env.lightSummary) logInfo("ibl: " + what + ": " + line);
    }
    progress("bright sources extracted");
    ShCoefficients sh = projectEquirectSh(map, scene.environment.rotationDegrees);
    for (size_t i = 0; i < 9; ++i) env.sh[i] = glm::vec3(sh[i]);
    progress("SH (CPU, double) done");
    // The irradiance cube and the prefiltered chain read the residual's own cube (the sky keeps env.cube).
    gl::Texture residualCube;
    if (!env.lights.empty()) {
        residualCube = gl::makeTextureCube(GL_RGBA16F, env.cube.width, env.cube.levels, "ibl.residual");
        equirectToCube(map, scene.environment.rotationDegrees, residualCube, what, shaders);
    }
    const gl::Texture& source = env.lights.empty() ? env.cube : residualCube;

    gl::ScopedEnable seamless(GL_TEXTURE_CUBE_MAP_SEAMLESS, true);
    // GPU time of the bake itself (irradiance + prefiltered chain), apart from file reading and the CPU SH.
    gl::Query gpuBegin = gl::makeQuery(GL_TIMESTAMP), gpuEnd = gl::makeQuery(GL_TIMESTAMP);
    glQueryCounter(gpuBegin.id(), GL_TIMESTAMP);
    const float sourceMaxLod = float(source.levels - 1);
    glBindTextureUnit(0, source.id());

    // Irradiance cube.
    if (!irradiance_) irradiance_ = shaders.compute("ibl_irradiance.comp");
    GLuint prog = irradiance_.id();
    glProgramUniform1i(prog, gl::Uniforms(&shaders, prog).location("uSize"), s.irradianceSize);
    glProgramUniform1i(prog, gl::Uniforms(&shaders, prog).location("uSamples"), s.irradianceSamples);
    glProgramUniform1i(prog, gl::Uniforms(&shaders, prog).location("uSourceSize"), source.width);
    glProgramUniform1f(prog, gl::Uniforms(&shaders, prog).location("uSourceMaxLod"), sourceMaxLod);
    glBindImageTexture(0, env.irradiance.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glUseProgram(prog);
    dispatchCube(s.irradianceSize);
    if (env.hasMap) glFinish();  // its own progress step
    progress("irradiance cube " + std::to_string(s.irradianceSize) + "^2 x " + std::to_string(s.irradianceSamples) +
             " samples recorded");

    // Specular: mip 0 (roughness 0) is an exact copy of the cube mip of that size (Filament #3093).
    const int sourceLevel = log2Int(s.cubeSize / s.specularSize);
    glCopyImageSubData(source.id(), GL_TEXTURE_CUBE_MAP, sourceLevel, 0, 0, 0, env.prefiltered.id(),
                       GL_TEXTURE_CUBE_MAP, 0, 0, 0, 0, s.specularSize, s.specularSize, 6);
    if (!prefilter_) prefilter_ = shaders.compute("ibl_prefilter.comp");
    prog = prefilter_.id();
    glProgramUniform1i(prog, gl::Uniforms(&shaders, prog).location("uSamples"), s.specularSamples);
    glProgramUniform1i(prog, gl::Uniforms(&shaders, prog).location("uSourceSize"), source.width);
    glProgramUniform1f(prog, gl::Uniforms(&shaders, prog).location("uSourceMaxLod"), sourceMaxLod);
    glUseProgram(prog);
    for (int level = 1; level < s.specularLevels; ++level) {
        const int size = std::max(s.specularSize >> level, 1);
        const float roughness = prefilteredLevelRoughness(level, s.specularLevels);
        glProgramUniform1i(prog, gl::Uniforms(&shaders, prog).location("uSize"), size);
        glProgramUniform1f(prog, gl::Uniforms(&shaders, prog).location("uRoughness"), roughness);
        glBindImageTexture(0, env.prefiltered.id(), level, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        dispatchCube(size);
        if (env.hasMap) {
            glFinish();  // per-level progress and a bounded time per submission
            progress("prefiltered mip " + std::to_string(level) + "/" + std::to_string(s.specularLevels - 1) +
                     " (roughness " + fmt(roughness) + ", " + std::to_string(size) + "^2, " +
                     std::to_string(s.specularSamples) + " samples) at " + fmt(std::round(secondsSince(t0) * 1000.0)) + " ms");
        }
    }
    glUseProgram(0);
    glBindTextureUnit(0, 0);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glQueryCounter(gpuEnd.id(), GL_TIMESTAMP);
    gl::checkErrors("baking image-based lighting");
    glFinish();
    bakeProgress.finish();  // before the summary line below
    env.bakeKey = key;
    GLuint64 gpuT0 = 0, gpuT1 = 0;
    glGetQueryObjectui64v(gpuBegin.id(), GL_QUERY_RESULT, &gpuT0);
    glGetQueryObjectui64v(gpuEnd.id(), GL_QUERY_RESULT, &gpuT1);
    env.bakeGpuMs = double(gpuT1 - gpuT0) * 1e-6;
    lastBakeGpuMs_ = env.bakeGpuMs;
    if (env.hasMap)
        logInfo("ibl: baked " + what + " in " + fmt(std::round(secondsSince(t0) * 1000.0)) + " ms (GPU " +
                fmt(float(std::round(env.bakeGpuMs * 100.0) / 100.0)) + " ms: irradiance " + std::to_string(s.irradianceSize) + "^2 x " +
                std::to_string(s.irradianceSamples) + ", prefiltered " + std::to_string(s.specularSize) + "^2 x " +
                std::to_string(s.specularLevels) + " mips x " + std::to_string(s.specularSamples) + " samples)");
    if (useDisk) saveCache(file, key, &env.sh, &env.lights, {&env.prefiltered, &env.irradiance});
}

void EnvironmentCache::forgetBakes() {
    for (auto& entry : environments_) entry.second->bakeKey.clear();
    lastBakeGpuMs_ = 0.0;
}

const gl::Texture& EnvironmentCache::dfgLut(const EnvironmentSettings& s, SpecularMasking masking,
                                            const gl::ShaderLibrary& shaders) {
    validateEnvironmentSettings(s);
    const std::string key = dfgKeyOf(s, masking);
    if (dfg_ && dfgKey_ == key) return dfg_;
    dfg_ = gl::makeTexture2D(GL_RG16F, s.dfgSize, s.dfgSize, 1, "ibl.dfg_lut");
    glTextureParameteri(dfg_.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(dfg_.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(dfg_.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(dfg_.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    if (!dfgProgram_) dfgProgram_ = shaders.compute("ibl_dfg.comp");
    const GLuint prog = dfgProgram_.id();
    glProgramUniform1i(prog, gl::Uniforms(&shaders, prog).location("uSize"), s.dfgSize);
    glProgramUniform1i(prog, gl::Uniforms(&shaders, prog).location("uSamples"), s.dfgSamples);
    glProgramUniform1i(prog, gl::Uniforms(&shaders, prog).location("uSpecularMasking"), int(masking));
    glBindImageTexture(0, dfg_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG16F);
    glUseProgram(prog);
    gl::dispatch2D(s.dfgSize, s.dfgSize);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    glUseProgram(0);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG16F);
    gl::checkErrors("computing the DFG LUT");
    dfgKey_ = key;
    return dfg_;
}

}  // namespace lp
