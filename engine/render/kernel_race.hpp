#pragma once
// Two GPU kernels that make the same image, chosen per view by their measured time. Which one is
// faster depends on the view and not only on the GPU (the clustered method's froxel kernel pays where
// tiles span near and far, and loses to the tiled kernel on continuous surfaces), so a start-up
// measurement cannot settle it: each round runs the two alternately until both have kSamples times,
// then the one with the smaller median runs until the key (what the pass was set up for: light count,
// size, settings) changes or kRecheckFrames frames pass and a new round starts (the camera may have
// moved). Pure: the caller times the kernel it was told to run and reports the time when its query
// is read, frames later.
#include <array>
#include <cstdint>
#include <vector>

namespace lp {

struct KernelRace {
    static constexpr int kSamples = 3;          // times per kernel in a round (a median of three)
    static constexpr int kRecheckFrames = 240;  // frames between rounds with an unchanged key
    std::uint64_t key = 0;
    bool keySet = false;
    bool racing = false;   // a round is under way: the kernels alternate
    int choice = 0;        // the kernel that runs outside rounds: the last round's winner (0 at first)
    int lastRun = -1;      // the kernel the last frame ran
    int framesSinceRound = 0;
    int rounds = 0;        // rounds begun since the race was made (tests)
    std::array<std::vector<double>, 2> times;    // this round's ms per kernel
    std::array<double, 2> lastMedians{-1.0, -1.0};  // the last finished round's medians (-1: none)
};

// Which kernel (0 or 1) runs this frame under `key`: a new key, or kRecheckFrames frames after the
// last round, begins a round. `timed` says whether the caller should time it (during rounds only).
int kernelRaceNext(KernelRace& race, std::uint64_t key, bool& timed);
// A time measured for `kernel` under `key` (ignored when the key has changed since, or no round is
// under way). The round ends when both kernels have kSamples times: the smaller median wins, a tie
// keeps the current choice.
void kernelRaceRecord(KernelRace& race, std::uint64_t key, int kernel, double ms);

}  // namespace lp
