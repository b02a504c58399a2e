// --post-backend auto: the per-effect choice from measured times and the timing cache file
// (engine/post/backend_timings, passes/post_backend). No GL: measurements are given.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>

#include <unistd.h>

#include "engine/core/measured_cache.hpp"
#include "engine/post/backend_timings.hpp"
#include "passes/post_backend.hpp"

using namespace lp;
using post::BackendTimes;
using post::PostEffect;

namespace {

std::filesystem::path scratchDir(const std::string& name) {
    auto dir = std::filesystem::temp_directory_path() / ("lightpass_post_cache_" + name + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

void writeText(const std::filesystem::path& p, const std::string& text) { std::ofstream(p) << text; }

post::TimingKey key1080(int kernel) {
    post::TimingKey k;
    k.gpu = "NVIDIA H100 80GB HBM3";
    k.driver = "4.6.0 NVIDIA 550.54.15";
    k.width = 1920;
    k.height = 1080;
    k.kernel = kernel;
    k.method = "separable";
    k.interop = "external";
    return k;
}

}  // namespace

TEST(PostBackendChoice, PicksTheFasterBackendPerEffect) {
    const PostBackendChoice c = chooseByTimes({{PostEffect::Bloom, {0.10, 0.20}},      // CUDA faster
                                               {PostEffect::Composite, {0.05, 0.03}},  // GLSL faster
                                               {PostEffect::Toon, {0.40, 0.41}}});     // CUDA faster
    EXPECT_TRUE(c.bloom);
    EXPECT_FALSE(c.composite);
    EXPECT_TRUE(c.toon);
    const PostBackendChoice flipped = chooseByTimes({{PostEffect::Bloom, {0.30, 0.20}}, {PostEffect::Toon, {0.1, 0.5}}});
    EXPECT_FALSE(flipped.bloom);
    EXPECT_FALSE(flipped.composite);  // not measured: GLSL
    EXPECT_TRUE(flipped.toon);
}

// --cuda-interop auto: shared textures (semaphores) only where the frame's post effects cost less on
// them than on map/unmap; under auto each effect counts at the faster of CUDA and GLSL, under
// --post-backend cuda at its CUDA time.
TEST(PostBackendChoice, SharedInteropOnlyWhereMeasuredCheaper) {
    using Times = std::map<PostEffect, BackendTimes>;
    const Times shared{{PostEffect::Bloom, {0.09, 0.10}}, {PostEffect::Composite, {0.02, 0.03}}};
    const Times mapped{{PostEffect::Bloom, {0.45, 0.10}}, {PostEffect::Composite, {0.30, 0.03}}};
    EXPECT_NEAR(postEffectsMs(shared, false), 0.11, 1e-12);
    EXPECT_NEAR(postEffectsMs(mapped, false), 0.13, 1e-12);  // auto runs GLSL for both on map
    EXPECT_NEAR(postEffectsMs(mapped, true), 0.75, 1e-12);
    EXPECT_TRUE(sharedInteropWins(shared, mapped, false));
    EXPECT_TRUE(sharedInteropWins(shared, mapped, true));
    // Shared slower in CUDA than GLSL and map: auto's frame costs the same either way (GLSL): a tie keeps map.
    const Times slowShared{{PostEffect::Bloom, {0.74, 0.10}}, {PostEffect::Composite, {0.50, 0.03}}};
    EXPECT_FALSE(sharedInteropWins(slowShared, mapped, false));
    EXPECT_FALSE(sharedInteropWins(slowShared, mapped, true));  // 1.24 > 0.75
    // Not measured on shared, or the effects differ: map.
    EXPECT_FALSE(sharedInteropWins({{PostEffect::Bloom, {-1.0, 0.10}}, {PostEffect::Composite, {0.02, 0.03}}}, mapped, false));
    EXPECT_FALSE(sharedInteropWins({{PostEffect::Bloom, {0.09, 0.10}}}, mapped, false));
    EXPECT_FALSE(sharedInteropWins({}, {}, false));
    EXPECT_LT(postEffectsMs({{PostEffect::Toon, {0.1, -1.0}}}, false), 0.0);
}

TEST(PostBackendChoice, TiesAndUnmeasuredTimesPickGlsl) {
    EXPECT_FALSE(post::cudaWins({0.2, 0.2}));
    EXPECT_FALSE(post::cudaWins({-1.0, 0.2}));
    EXPECT_FALSE(post::cudaWins({0.1, -1.0}));
    EXPECT_TRUE(post::cudaWins({0.1, 0.2}));
}

TEST(PostBackendChoice, KeyNamesEveryField) {
    post::TimingKey k = key1080(5);
    k.effect = PostEffect::Composite;
    EXPECT_EQ(k.text(), "NVIDIA H100 80GB HBM3|4.6.0 NVIDIA 550.54.15|1920x1080|kernel 5|separable|external|composite");
    post::TimingKey other = k;
    other.kernel = 100;
    EXPECT_NE(other.text(), k.text());
    other = k;
    other.interop = "map";
    EXPECT_NE(other.text(), k.text());
}

TEST(PostTimingCache, WritesAndReadsBack) {
    const auto dir = scratchDir("roundtrip");
    const auto file = dir / "sub" / "measured_choices.json";  // the folder is made
    post::TimingCache entries{{"a|b|1x1|kernel 1|separable|map|bloom", {0.25, 0.5}},
                              {"a|b|1x1|kernel 1|separable|map|toon", {1.0, 0.125}}};
    EXPECT_EQ(post::writeTimingCache(file, entries), "");
    const post::CacheRead read = post::readTimingCache(file);
    EXPECT_EQ(read.warning, "");
    ASSERT_EQ(read.entries.size(), 2u);
    EXPECT_DOUBLE_EQ(read.entries.at("a|b|1x1|kernel 1|separable|map|bloom").cudaMs, 0.25);
    EXPECT_DOUBLE_EQ(read.entries.at("a|b|1x1|kernel 1|separable|map|toon").glslMs, 0.125);
    EXPECT_FALSE(std::filesystem::exists(file.string() + ".tmp"));
    std::filesystem::remove_all(dir);
}

TEST(PostTimingCache, MissingFileIsEmptyWithoutWarning) {
    const post::CacheRead read = post::readTimingCache(scratchDir("missing") / "none.json");
    EXPECT_TRUE(read.entries.empty());
    EXPECT_EQ(read.warning, "");
}

TEST(PostTimingCache, CorruptFilesWarnNamingTheFileAndReadEmpty) {
    const auto dir = scratchDir("corrupt");
    const std::pair<const char*, const char*> cases[] = {
        {"{\"version\": 1, \"sections\": {", "not valid JSON"},
        {"[1, 2]", "not a version 1"},
        {"{\"version\": 7, \"sections\": {}}", "not a version 1"},
        {"{\"version\": 1}", "no \"sections\""},
        {"{\"version\": 1, \"sections\": {\"post_backend\": [1]}}", "not an object"},
        {"{\"version\": 1, \"sections\": {\"post_backend\": {\"k\": {\"cuda_ms\": \"fast\", \"glsl_ms\": 1}}}}", "needs numbers"},
        {"{\"version\": 1, \"sections\": {\"post_backend\": {\"k\": {\"cuda_ms\": -2, \"glsl_ms\": 1}}}}", "negative or non-finite"},
        {"", "not valid JSON"},
    };
    for (const auto& [text, expected] : cases) {
        const auto file = dir / "measured_choices.json";
        writeText(file, text);
        const post::CacheRead read = post::readTimingCache(file);
        EXPECT_TRUE(read.entries.empty()) << text;
        EXPECT_NE(read.warning.find(file.string()), std::string::npos) << read.warning;
        EXPECT_NE(read.warning.find(expected), std::string::npos) << text << " -> " << read.warning;
        EXPECT_NE(read.warning.find("measuring again"), std::string::npos) << read.warning;
    }
    std::filesystem::remove_all(dir);
}

// The post backend's times share the measurement cache with other choices: writing them keeps the
// other sections whole.
TEST(PostTimingCache, KeepsTheOtherSectionsOfTheMeasurementCache) {
    const auto dir = scratchDir("sections");
    const auto file = dir / "measured_choices.json";
    const nlohmann::json shadow = {{"Some GPU / 4.5", "compute"}};
    ASSERT_EQ(writeMeasuredSection(file, "shadow_raster", shadow), "");
    EXPECT_EQ(post::writeTimingCache(file, {{"a|b|1x1|kernel 1|separable|map|bloom", {0.25, 0.5}}}), "");
    EXPECT_EQ(readMeasuredSection(file, "shadow_raster").entries, shadow);
    EXPECT_EQ(post::readTimingCache(file).entries.size(), 1u);
    std::filesystem::remove_all(dir);
}

TEST(MeasuredCache, PathFollowsTheEnvironmentAndNeverTheWorkingDirectory) {
    auto env = [](std::map<std::string, std::string> vars) {
        return [vars](const char* name) -> const char* {
            auto it = vars.find(name);
            return it == vars.end() ? nullptr : it->second.c_str();
        };
    };
    EXPECT_EQ(measuredCachePath(env({{"LIGHTPASS_CACHE_DIR", "/c"}, {"HOME", "/h"}})),
              std::filesystem::path("/c/measured_choices.json"));
    EXPECT_EQ(measuredCachePath(env({{"XDG_CACHE_HOME", "/x"}, {"HOME", "/h"}})),
              std::filesystem::path("/x/lightpass/measured_choices.json"));
    EXPECT_EQ(measuredCachePath(env({{"XDG_CACHE_HOME", "relative"}, {"HOME", "/h"}})),
              std::filesystem::path("/h/.cache/lightpass/measured_choices.json"));
    EXPECT_EQ(measuredCachePath(env({})), std::filesystem::path());
}

// autoChoice measures what the cache lacks, writes it, and reads it back in a later process
// (a fresh PostBackend) without measuring; a corrupt file is remeasured and rewritten.
TEST(PostBackendAuto, MeasuresOnceThenUsesTheCache) {
    const auto dir = scratchDir("auto");
    const std::vector<PostEffect> effects{PostEffect::Bloom, PostEffect::Composite};
    int measured = 0;
    auto measure = [&](PostEffect e) {
        ++measured;
        return e == PostEffect::Bloom ? BackendTimes{0.1, 0.2} : BackendTimes{0.3, 0.2};
    };
    {
        PostBackend backend;
        backend.cacheFile = dir / "measured_choices.json";
        const PostBackendChoice c = backend.autoChoice(key1080(5), effects, false, measure);
        EXPECT_TRUE(c.bloom);
        EXPECT_FALSE(c.composite);
        EXPECT_EQ(measured, 2);
        backend.autoChoice(key1080(5), effects, false, measure);  // same process: decided already
        EXPECT_EQ(measured, 2);
        backend.autoChoice(key1080(100), effects, false, measure);  // another kernel: measured
        EXPECT_EQ(measured, 4);
    }
    {
        PostBackend later;
        later.cacheFile = dir / "measured_choices.json";
        const PostBackendChoice c = later.autoChoice(key1080(5), effects, false, measure);
        EXPECT_EQ(measured, 4);  // from the file
        EXPECT_TRUE(c.bloom);
        EXPECT_FALSE(c.composite);
        later.autoChoice(key1080(5), effects, true, measure);  // --post-remeasure
        EXPECT_EQ(measured, 6);
    }
    writeText(dir / "measured_choices.json", "{ not json");
    {
        PostBackend afterCorruption;
        afterCorruption.cacheFile = dir / "measured_choices.json";
        const PostBackendChoice c = afterCorruption.autoChoice(key1080(5), effects, false, measure);
        EXPECT_EQ(measured, 8);
        EXPECT_TRUE(c.bloom);
        EXPECT_EQ(post::readTimingCache(dir / "measured_choices.json").warning, "");  // rewritten whole
    }
    std::filesystem::remove_all(dir);
}

// A measurement that failed (negative times) is not cached and leaves the effect on GLSL.
TEST(PostBackendAuto, FailedMeasurementIsNotCached) {
    const auto dir = scratchDir("failed");
    PostBackend backend;
    backend.cacheFile = dir / "measured_choices.json";
    const PostBackendChoice c =
        backend.autoChoice(key1080(5), {PostEffect::Toon}, false, [](PostEffect) { return BackendTimes{}; });
    EXPECT_FALSE(c.toon);
    EXPECT_TRUE(post::readTimingCache(backend.cacheFile).entries.empty());
    std::filesystem::remove_all(dir);
}
