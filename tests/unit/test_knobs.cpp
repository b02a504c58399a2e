// The sweep's knob registry: every knob is described, has at least two distinct values ordered
// cheapest first with the reference last, and each value changes the setting it names.
#include <gtest/gtest.h>

#include <set>

#include "frame/knobs.hpp"

using namespace lp;

TEST(Knobs, EveryQualityKnobIsRegisteredAndDescribed) {
    const std::set<std::string> expected = {"gbuffer-format", "gbuffer-position", "shadow-size", "shadow-pcf",
                                            "shadow-cascades", "ibl-samples", "ibl-face-size", "ibl-diffuse",
                                            "bloom-kernel", "bloom-method", "local-light-method", "light-range-cutoff",
                                            "render-scale", "motion-blur-samples",
                                            "aa", "ssaa-scale", "taa-history-weight"};
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
    const Knob* blur = findKnob("motion-blur-samples");
    ASSERT_NE(blur, nullptr);
    blur->values.front().apply(s);
    EXPECT_EQ(s.motionBlur.samples, 4);
    EXPECT_TRUE(s.motionBlur.enabled);  // a sample count means nothing with the blur off
    blur->values.back().apply(s);
    EXPECT_EQ(s.motionBlur.samples, 32);
    s = RenderSettings{};
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
    EXPECT_EQ(s.environment.specularSamples, 4096);

    const Knob* scale = findKnob("render-scale");
    scale->values.front().apply(s);
    EXPECT_FLOAT_EQ(s.renderScale, 0.25f);
    scale->values.back().apply(s);
    EXPECT_FLOAT_EQ(s.renderScale, 1.0f);

    EXPECT_FALSE(findKnob("local-light-method")->monotone);
    EXPECT_FALSE(findKnob("shadow-pcf")->monotone);
}

// "A+B": every combination, A slowest, both applied, the reference both references together.
TEST(Knobs, ProductOfKnobsSweepsEveryCombination) {
    std::optional<Knob> p = knobByName("shadow-size+shadow-pcf");
    ASSERT_TRUE(p.has_value());
    EXPECT_EQ(p->name, "shadow-size+shadow-pcf");
    EXPECT_FALSE(p->monotone);
    ASSERT_EQ(p->values.size(), 16u);
    EXPECT_EQ(p->values.front().label, "512/off");
    EXPECT_EQ(p->values[1].label, "512/3x3");
    EXPECT_EQ(p->values.back().label, "4096/poisson");
    std::set<std::string> labels;
    for (const KnobValue& v : p->values) EXPECT_TRUE(labels.insert(v.label).second) << v.label;
    RenderSettings s;
    s.shadows.enabled = false;
    p->values[6].apply(s);  // 1024 x 5x5
    EXPECT_TRUE(s.shadows.enabled);
    EXPECT_EQ(s.shadows.size, 1024);
    EXPECT_EQ(s.shadows.filter, ShadowSettings::Filter::Pcf5x5);
    p->values.back().apply(s);
    EXPECT_EQ(s.shadows.size, 4096);
    EXPECT_EQ(s.shadows.filter, ShadowSettings::Filter::Poisson);

    // Neither factor undoes the other: the bloom kernel keeps the method the product chose.
    std::optional<Knob> bloom = knobByName("bloom-method+bloom-kernel");
    ASSERT_TRUE(bloom.has_value());
    RenderSettings b;
    bloom->values.front().apply(b);
    EXPECT_EQ(bloom->values.front().label, "mip-chain/5");
    EXPECT_EQ(b.post.bloomMethod, PostSettings::BloomMethod::MipChain);
    EXPECT_EQ(b.post.bloomKernel, 5);

    std::optional<Knob> three = knobByName("ibl-samples+ibl-face-size+ibl-diffuse");
    ASSERT_TRUE(three.has_value());
    EXPECT_EQ(three->values.size(), 4u * 4u * 2u);
    EXPECT_EQ(three->values.back().label, "4096/512/cubemap");

    EXPECT_EQ(knobByName("render-scale")->values.size(), 4u);  // a single name is the knob itself
    EXPECT_FALSE(knobByName("shadow-size+bogus").has_value());
    EXPECT_FALSE(knobByName("shadow-size+shadow-size").has_value());
    EXPECT_FALSE(knobByName("shadow-size+").has_value());
    EXPECT_FALSE(knobByName("+shadow-size").has_value());
}

// --aa: off, fxaa and taa, then SSAA at 2x2 and 3x3 samples, against SSAA 4x4 (the reference, last).
// --ssaa-scale's values switch SSAA on. Every value is a setting the renderer accepts.
TEST(Knobs, AntiAliasingSweepEndsAtSsaa4x4) {
    const Knob* aa = findKnob("aa");
    ASSERT_NE(aa, nullptr);
    std::vector<std::string> labels;
    for (const KnobValue& v : aa->values) labels.push_back(v.label);
    EXPECT_EQ(labels, (std::vector<std::string>{"off", "fxaa", "taa", "ssaa2", "ssaa3", "ssaa4"}));
    EXPECT_FALSE(aa->monotone);
    const std::vector<std::pair<AntiAliasing, int>> expected = {
        {AntiAliasing::Off, 2}, {AntiAliasing::Fxaa, 2}, {AntiAliasing::Taa, 2},
        {AntiAliasing::Ssaa, 2}, {AntiAliasing::Ssaa, 3}, {AntiAliasing::Ssaa, 4}};
    for (size_t i = 0; i < aa->values.size(); ++i) {
        RenderSettings s;
        aa->values[i].apply(s);
        EXPECT_EQ(s.aa.method, expected[i].first) << labels[i];
        EXPECT_EQ(s.aa.ssaaScale, expected[i].second) << labels[i];
    }
    const Knob* scale = findKnob("ssaa-scale");
    ASSERT_NE(scale, nullptr);
    EXPECT_TRUE(scale->monotone);
    RenderSettings s;
    scale->values.back().apply(s);
    EXPECT_EQ(s.aa.method, AntiAliasing::Ssaa);
    EXPECT_EQ(s.aa.ssaaScale, kMaxSsaaScale);
}
