// The sweep's knob registry: every knob is described, has at least two distinct values ordered
// cheapest first with the reference last, and each value changes the setting it names.
#include <gtest/gtest.h>

#include <set>

#include "engine/render/knobs.hpp"

using namespace lp;

TEST(Knobs, EveryQualityKnobIsRegisteredAndDescribed) {
    const std::set<std::string> expected = {"gbuffer-format", "gbuffer-position", "shadow-size", "shadow-pcf",
                                            "shadow-cascades", "ibl-samples", "ibl-face-size", "ibl-diffuse",
                                            "bloom-kernel", "bloom-method", "local-light-method", "light-range-cutoff"};
    std::set<std::string> names;
    for (const Knob& k : allKnobs()) {
        EXPECT_TRUE(names.insert(k.name).second) << "duplicate knob " << k.name;
        EXPECT_FALSE(k.description.empty()) << k.name;
        EXPECT_GE(k.values.size(), 2u) << k.name;
        std::set<std::string> labels;
        for (const KnobValue& v : k.values) EXPECT_TRUE(labels.insert(v.label).second) << k.name << " " << v.label;
        EXPECT_EQ(findKnob(k.name), &k);
    }
    for (const auto& n : expected) EXPECT_TRUE(names.count(n)) << n;
    EXPECT_EQ(findKnob("bogus"), nullptr);
}

// Spot checks that values reach the settings and that the reference is the best value.
TEST(Knobs, ValuesSetWhatTheyNameAndTheReferenceIsLast) {
    RenderSettings s;
    const Knob* size = findKnob("shadow-size");
    ASSERT_NE(size, nullptr);
    size->values.front().apply(s);
    EXPECT_EQ(s.shadows.size, 512);
    size->values.back().apply(s);
    EXPECT_EQ(s.shadows.size, 4096);

    const Knob* format = findKnob("gbuffer-format");
    ASSERT_NE(format, nullptr);
    EXPECT_FALSE(format->monotone);
    format->values.front().apply(s);
    EXPECT_EQ(s.gbuffer.normal, GBufferNormalFormat::Oct16);
    format->values.back().apply(s);
    EXPECT_EQ(s.gbuffer.normal, GBufferNormalFormat::Unpacked);

    const Knob* position = findKnob("gbuffer-position");
    position->values.back().apply(s);
    EXPECT_EQ(s.gbuffer.position, GBufferPositionMode::Stored);

    const Knob* range = findKnob("light-range-cutoff");
    range->values.front().apply(s);
    EXPECT_FLOAT_EQ(s.localLights.rangeScale, 0.25f);
    range->values.back().apply(s);
    EXPECT_FLOAT_EQ(s.localLights.rangeScale, 1.0f);

    const Knob* bloom = findKnob("bloom-kernel");
    bloom->values.back().apply(s);
    EXPECT_EQ(s.post.bloom, true);
    EXPECT_EQ(s.post.bloomKernel, 100);

    const Knob* samples = findKnob("ibl-samples");
    samples->values.back().apply(s);
    EXPECT_EQ(s.environment.ibl, true);
    EXPECT_EQ(s.environment.specularSamples, 1024);

    EXPECT_FALSE(findKnob("local-light-method")->monotone);
    EXPECT_FALSE(findKnob("shadow-pcf")->monotone);
}
