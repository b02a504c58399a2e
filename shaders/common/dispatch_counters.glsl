// Counters a dispatch reports to the CPU (MappedCounterRing in passes/local_light_pass): the CPU reads
// uCounters from a persistently mapped buffer, which lives in host memory, where every atomic would
// cross the bus (a same-address atomic per work group cost milliseconds). So each work group adds
// into the device-local uTally, and the last group to finish copies the totals into uCounters and
// zeroes uTally for the next dispatch.
#ifndef LP_DISPATCH_COUNTERS_GLSL
#define LP_DISPATCH_COUNTERS_GLSL

layout(std430, binding = 3) writeonly buffer DispatchCounters { uint uCounters[4]; };
layout(std430, binding = 6) buffer DispatchTally { uint uTally[5]; };  // [4]: work groups finished
uniform uint uGroupCount;  // work groups in the dispatch

// Adds n to counter i (0..3).
void tallyCounter(int i, uint n) {
    if (n != 0u) atomicAdd(uTally[i], n);
}

// Every invocation, in uniform control flow, after its group's last tallyCounter.
void finishDispatchCounters() {
    memoryBarrierBuffer();
    barrier();
    if (gl_LocalInvocationIndex == 0u && atomicAdd(uTally[4], 1u) + 1u == uGroupCount) {
        memoryBarrierBuffer();
        for (int i = 0; i < 4; ++i) uCounters[i] = atomicExchange(uTally[i], 0u);
        atomicExchange(uTally[4], 0u);
    }
}

#endif
