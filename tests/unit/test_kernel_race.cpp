// The race between two kernels that make the same image (engine/render/kernel_race.hpp): which one
// runs each frame, that the faster median wins, that times arriving late or for an old key are
// handled, and that rounds begin again on a new key and every kRecheckFrames frames.
#include <deque>
#include <tuple>
#include <utility>

#include <gtest/gtest.h>

#include "engine/render/kernel_race.hpp"

namespace lp {
namespace {

// Runs `frames` frames under `key`: each timed run's time (ms[kernel]) is reported `latency` frames
// later, as the pass reads its queries. Returns how many frames ran each kernel.
std::pair<int, int> runFrames(KernelRace& race, std::uint64_t key, int frames, double ms0, double ms1, int latency,
                              std::deque<std::pair<int, int>>& inFlight, int& frame) {
    int ran[2] = {0, 0};
    for (int f = 0; f < frames; ++f, ++frame) {
        while (!inFlight.empty() && inFlight.front().first + latency <= frame) {
            const int kernel = inFlight.front().second;
            kernelRaceRecord(race, key, kernel, kernel == 0 ? ms0 : ms1);
            inFlight.pop_front();
        }
        bool timed = false;
        const int k = kernelRaceNext(race, key, timed);
        ++ran[k];
        if (timed) inFlight.emplace_back(frame, k);
    }
    return {ran[0], ran[1]};
}

TEST(KernelRace, TheFasterKernelWinsAndRunsOutsideRounds) {
    for (const auto& [ms0, ms1, winner] : {std::tuple{0.30, 0.25, 1}, std::tuple{0.20, 0.25, 0}}) {
        KernelRace race;
        std::deque<std::pair<int, int>> inFlight;
        int frame = 0;
        const auto [round0, round1] = runFrames(race, 7, 20, ms0, ms1, 3, inFlight, frame);
        EXPECT_FALSE(race.racing) << "the round ends once both have their samples";
        EXPECT_EQ(race.choice, winner);
        EXPECT_DOUBLE_EQ(race.lastMedians[0], ms0);
        EXPECT_DOUBLE_EQ(race.lastMedians[1], ms1);
        EXPECT_GE(round0, KernelRace::kSamples);
        EXPECT_GE(round1, KernelRace::kSamples);
        // Until the next round, only the winner runs.
        const auto [later0, later1] = runFrames(race, 7, 100, ms0, ms1, 3, inFlight, frame);
        EXPECT_EQ(winner == 0 ? later1 : later0, 0);
        EXPECT_EQ(race.rounds, 1);
    }
}

TEST(KernelRace, TheMedianIgnoresOneSlowSample) {
    KernelRace race;
    bool timed = false;
    // The first run of kernel 0 (say a cold cache) is slow; its median is still below kernel 1's.
    const double times0[] = {5.0, 0.20, 0.21}, times1[] = {0.30, 0.31, 0.29};
    int at0 = 0, at1 = 0;
    for (int f = 0; f < 12; ++f) {
        const int k = kernelRaceNext(race, 1, timed);
        ASSERT_TRUE(timed);
        kernelRaceRecord(race, 1, k, k == 0 ? times0[at0++ % 3] : times1[at1++ % 3]);
        if (!race.racing) break;
    }
    EXPECT_FALSE(race.racing);
    EXPECT_EQ(race.choice, 0);
    EXPECT_DOUBLE_EQ(race.lastMedians[0], 0.21);
}

TEST(KernelRace, ANewKeyOrTheRecheckBeginsARound) {
    KernelRace race;
    std::deque<std::pair<int, int>> inFlight;
    int frame = 0;
    runFrames(race, 1, 20, 0.3, 0.2, 2, inFlight, frame);
    ASSERT_EQ(race.choice, 1);
    ASSERT_EQ(race.rounds, 1);
    // The view changed so that kernel 0 is now faster: the next round (after kRecheckFrames) finds it.
    runFrames(race, 1, KernelRace::kRecheckFrames + 20, 0.1, 0.2, 2, inFlight, frame);
    EXPECT_EQ(race.rounds, 2);
    EXPECT_EQ(race.choice, 0);
    // Another key (more lights, another size) begins a round at once; a time measured under the old
    // key and read after the change is not counted in it.
    bool timed = false;
    kernelRaceNext(race, 2, timed);
    EXPECT_TRUE(timed);
    EXPECT_EQ(race.rounds, 3);
    kernelRaceRecord(race, 1, 1, 0.01);
    EXPECT_TRUE(race.times[1].empty());
}

TEST(KernelRace, KernelsAlternateAndATieKeepsTheChoice) {
    KernelRace race;
    bool timed = false;
    int last = -1;
    for (int f = 0; f < 2 * KernelRace::kSamples; ++f) {
        const int k = kernelRaceNext(race, 3, timed);
        if (f == 0) EXPECT_EQ(k, 0) << "a round begins with the current choice";
        if (last >= 0) EXPECT_NE(k, last) << "frame " << f;
        last = k;
    }
    for (int k = 0; k < 2; ++k)
        for (int i = 0; i < KernelRace::kSamples; ++i) kernelRaceRecord(race, 3, k, 0.5);
    EXPECT_FALSE(race.racing);
    EXPECT_EQ(race.choice, 0);
}

}  // namespace
}  // namespace lp
