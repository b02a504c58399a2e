#include "engine/render/kernel_race.hpp"

#include "engine/gl/gpu_timer.hpp"

namespace lp {

namespace {
void beginRound(KernelRace& race) {
    race.racing = true;
    race.framesSinceRound = 0;
    race.times[0].clear();
    race.times[1].clear();
    ++race.rounds;
}
bool needs(const KernelRace& race, int kernel) { return int(race.times[size_t(kernel)].size()) < KernelRace::kSamples; }
}  // namespace

int kernelRaceNext(KernelRace& race, std::uint64_t key, bool& timed) {
    if (!race.keySet || race.key != key) {
        race.key = key;
        race.keySet = true;
        beginRound(race);
    } else if (!race.racing && ++race.framesSinceRound >= KernelRace::kRecheckFrames) {
        beginRound(race);
    }
    timed = race.racing;
    int next = race.choice;
    if (race.racing) {
        // Alternate while both still need times (starting with the current choice); once one has
        // its samples, the other runs until its times are in (they arrive a few frames late).
        const bool need0 = needs(race, 0), need1 = needs(race, 1);
        if (need0 && need1)
            next = race.lastRun < 0 ? race.choice : 1 - race.lastRun;
        else if (need0 != need1)
            next = need0 ? 0 : 1;
    }
    race.lastRun = next;
    return next;
}

void kernelRaceRecord(KernelRace& race, std::uint64_t key, int kernel, double ms) {
    if (!race.keySet || race.key != key || !race.racing || kernel < 0 || kernel > 1) return;
    if (!needs(race, kernel)) return;
    race.times[size_t(kernel)].push_back(ms);
    if (needs(race, 0) || needs(race, 1)) return;
    const double m0 = gl::median(race.times[0]), m1 = gl::median(race.times[1]);
    race.lastMedians = {m0, m1};
    if (m0 < m1) race.choice = 0;
    else if (m1 < m0) race.choice = 1;
    race.racing = false;
    race.framesSinceRound = 0;
}

}  // namespace lp
