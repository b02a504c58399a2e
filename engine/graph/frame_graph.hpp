#pragma once
// The frame graph (after Frostbite's FrameGraph and Filament's fg). Passes declare in setup what they
// create, read and write; compile() culls every pass whose writes reach nothing the outputs need,
// orders the rest, and gives each transient texture a lifetime so the pool can reuse memory.
//
// Resources are versioned: write(h) returns a new version, so "bloom reads the HDR buffer before the
// composite writes into it" is expressible. A read may also name a resource by string; it resolves at
// compile time to that resource's last version (forward references, e.g. a debug view declared
// before the G-buffer), which is also how a misdeclared graph can form a cycle, reported by compile().
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "engine/gl/gl.hpp"

namespace lp::gl {
class GpuTimerRing;
}

namespace lp::fg {

struct TextureDesc {
    int width = 0;
    int height = 0;
    GLenum format = GL_RGBA16F;
    int levels = 1;
    bool operator==(const TextureDesc& o) const {
        return width == o.width && height == o.height && format == o.format && levels == o.levels;
    }
    size_t bytes() const;
};

struct ResourceId {
    int version = -1;  // index into the graph's version table
    bool valid() const { return version >= 0; }
};

class FrameGraph;
class TexturePool;

class PassBuilder {
public:
    ResourceId create(const std::string& name, const TextureDesc& desc);
    // A target the pass can do without (a G-buffer channel): allocated only when some live pass
    // reads it or it is an output; otherwise PassResources::texture() gives 0 and the writer skips it.
    ResourceId createIfRead(const std::string& name, const TextureDesc& desc);
    ResourceId read(ResourceId id);
    ResourceId read(const std::string& resourceName);  // resolves at compile time to the last version
    ResourceId write(ResourceId id);                   // read-modify-write: returns the new version
    void sideEffect();                                 // never culled (presents, readbacks)

private:
    friend class FrameGraph;
    PassBuilder(FrameGraph& g, int pass) : graph_(g), pass_(pass) {}
    FrameGraph& graph_;
    int pass_;
};

class PassResources {
public:
    GLuint texture(ResourceId id) const;
    const TextureDesc& desc(ResourceId id) const;
    // The timer ring of this execute (null when untimed): passes timed outside GL (CUDA events)
    // report through GpuTimerRing::addExternal.
    gl::GpuTimerRing* timers() const { return timers_; }

private:
    friend class FrameGraph;
    PassResources(const FrameGraph& g, gl::GpuTimerRing* timers) : graph_(g), timers_(timers) {}
    const FrameGraph& graph_;
    gl::GpuTimerRing* timers_ = nullptr;
};

using SetupFn = std::function<void(PassBuilder&)>;
using ExecuteFn = std::function<void(const PassResources&)>;

struct PassReport {
    std::string name;
    bool culled = false;
    bool disabled = false;            // switched off by the user
    std::string reason;               // why it was culled or disabled
    std::vector<std::string> reads;   // "gbuffer.normal", "hdr@1" for later versions
    std::vector<std::string> writes;
};

struct ResourceReport {
    std::string name;
    TextureDesc desc;
    bool imported = false;
    bool live = false;
    int firstPass = -1, lastPass = -1;  // in execution order
};

// One candidate pass of a frame: it runs, or why not (culled, disabled, or skipped by the builder).
struct PassDecision {
    std::string name;
    bool runs = false;
    std::string reason;  // "skipped: scene has no shadow-casting light"; empty when it runs
};

class FrameGraph {
public:
    // Runs `setup` now; `execute` runs in execute() if the pass survives compile().
    void addPass(const std::string& name, const SetupFn& setup, ExecuteFn execute);
    // Frostbite-style: setup fills a Data struct (the handles it declared) that execute receives.
    template <typename Data>
    const Data& addPass(const std::string& name, const std::function<void(PassBuilder&, Data&)>& setup,
                        std::function<void(const Data&, const PassResources&)> execute) {
        auto data = std::make_shared<Data>();
        addPass(
            name, [&](PassBuilder& b) { setup(b, *data); },
            [data, execute = std::move(execute)](const PassResources& r) { execute(*data, r); });
        return *data;
    }
    ResourceId importTexture(const std::string& name, const TextureDesc& desc, GLuint texture);
    // The graph's result(s): what is presented, saved or read back. At least one is required.
    void markOutput(ResourceId id);
    void markOutput(const std::string& resourceName);
    // The user switched a pass off: it contributes nothing. Its in-place writes pass their input
    // through (readers see the previous version); textures it creates are cleared to zero instead
    // of drawn, so the passes after it still run. Unknown names are ignored.
    void disablePass(const std::string& passName);
    // Records a pass the frame builder did not add because the scene or settings don't call for it
    // ("scene has no shadow-casting light"); shown by describe() and report(), never executed.
    void skipPass(const std::string& passName, const std::string& reason);
    const std::vector<std::pair<std::string, std::string>>& skippedPasses() const { return skipped_; }
    // Every candidate pass (added or skipped) with its decision, in the order they were considered;
    // after compile(). explainText() is what 'lightpass graph --explain' prints.
    std::vector<PassDecision> explain() const;
    std::string explainText() const;
    // Bytes of the live transient textures (before the pool reuses memory between lifetimes).
    size_t liveTransientBytes() const;

    // Throws lp::Error for a read of a resource nothing writes, a double write of one version,
    // a cycle, or a graph with no output.
    void compile();
    // Allocates transient textures from the pool, records every live pass in order, and releases
    // textures after their last use so later passes can reuse them.
    void execute(TexturePool& pool, gl::GpuTimerRing* timers = nullptr);

    const std::vector<PassReport>& report() const { return report_; }
    std::vector<std::string> executionOrder() const;
    std::vector<ResourceReport> resources() const;
    bool isLive(const std::string& passName) const;
    // Bytes a pass must move at least: every texel of what it reads plus what it writes (an
    // in-place write counts as a read and a write). The basis of its bandwidth floor.
    size_t passTrafficBytes(const std::string& passName) const;
    bool hasPass(const std::string& passName) const;
    // Text table and Graphviz DOT of the compiled graph.
    std::string describe() const;
    std::string toDot() const;
    // Texture id of a resource after execute() (outputs stay allocated until the next execute).
    GLuint outputTexture(const std::string& resourceName) const;
    GLuint outputTexture(ResourceId id) const;

private:
    friend class PassBuilder;
    friend class PassResources;
    struct Resource {
        std::string name;
        TextureDesc desc;
        GLuint imported = 0;
        bool isImported = false;
        std::vector<int> versions;
        GLuint texture = 0;  // bound during execute
        int first = -1, last = -1;
        bool live = false;
        bool output = false;
        bool optional = false;  // createIfRead: dropped when nothing live reads it
    };
    struct Version {
        int resource = -1;
        int number = 0;
        int writer = -1;  // pass index; -1 for v0 of an imported resource
        std::vector<int> readers;
    };
    struct Pass {
        std::string name;
        ExecuteFn execute;
        std::vector<int> reads;  // version indices
        std::vector<std::pair<int, std::string>> namedReads;  // resolved in compile
        std::vector<int> writes;
        bool sideEffect = false;
        bool live = false;
        bool disabled = false;
    };
    int newVersion(int resource, int writer);
    std::string versionName(int version) const;
    const Resource& resourceOf(ResourceId id) const;

    std::vector<Resource> resources_;
    std::vector<Version> versions_;
    std::vector<Pass> passes_;
    int resolve(int version) const;  // follows pass-through aliases of disabled passes
    std::vector<std::pair<std::string, std::string>> skipped_;
    std::vector<std::pair<bool, int>> candidates_;  // (added, index into passes_ or skipped_) in order
    std::vector<int> alias_;         // per version: the version it passes through to, or -1
    std::vector<int> outputs_;
    std::vector<std::string> namedOutputs_;
    std::vector<int> order_;
    std::vector<PassReport> report_;
    bool compiled_ = false;
};

}  // namespace lp::fg
