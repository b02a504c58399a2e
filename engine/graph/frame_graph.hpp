#pragma once
// The frame graph (after Frostbite's FrameGraph and Filament's fg). Passes declare in setup what they
// create, read and write; compile() culls every pass whose writes reach nothing the outputs need,
// orders the rest, and gives each transient texture a lifetime so the pool can reuse memory.
//
// Resources are versioned: write(h) returns a new version, so "bloom reads the HDR buffer before the
// composite writes into it" is expressible. A read may also name a resource by string; it resolves at
// compile time to that resource's last version (forward references, e.g. a debug view declared
// before the G-buffer), which is also how a misdeclared graph can form a cycle, reported by compile().
//
// Every read and write says how the pass touches the resource (Usage) and every pass says what kind
// of work it is (PassKind). From those the graph derives what passes used to hand-pick: the memory
// barriers between a producer's incoherent writes (image stores) and its consumers, the floor a pass
// is measured against (fill rate for raster, bandwidth for compute and CUDA), and a check that a
// pass only touches what it declared.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "engine/gl/gl.hpp"
#include "engine/gl/state_check.hpp"

namespace lp::gl {
class GpuTimerRing;
}

namespace lp::fg {

struct TextureDesc {
    int width = 0;
    int height = 0;
    GLenum format = GL_RGBA16F;
    int levels = 1;
    bool cube = false;  // six faces (imported environment cubes; the pool makes 2D textures only)
    bool operator==(const TextureDesc& o) const {
        return width == o.width && height == o.height && format == o.format && levels == o.levels && cube == o.cube;
    }
    size_t bytes() const;
};

// How a pass touches a resource; a bit set, since one pass may e.g. blend into a target and then
// fix it up with an image load/store. The graph turns a producer's incoherent writes (ImageStore)
// into the glMemoryBarrier bits its consumers' usages need; everything else GL orders by itself.
enum class Usage : uint32_t {
    Sampled = 1u << 0,          // texture() / texelFetch through a texture unit
    ImageLoad = 1u << 1,        // imageLoad
    ImageStore = 1u << 2,       // imageStore: incoherent, needs a barrier before the next use
    ColorAttachment = 1u << 3,  // drawn into (replaces)
    Blend = 1u << 4,            // drawn into with blending (reads the previous contents)
    DepthAttachment = 1u << 5,  // depth written by raster
    DepthTest = 1u << 6,        // bound as the depth attachment, tested, not written
    Transfer = 1u << 7,         // glClearTexImage, glGetTextureImage, copies
    Cuda = 1u << 8,             // mapped into CUDA (map and unmap synchronise with GL)
    StorageBuffer = 1u << 9,    // a buffer read (or written: incoherent) through a shader storage block
    VertexBuffer = 1u << 10,    // a buffer drawn from: vertex attributes, or copied into a pass's own (Transfer)
    ImageLoadStore = (1u << 1) | (1u << 2),
};
constexpr Usage operator|(Usage a, Usage b) { return Usage(uint32_t(a) | uint32_t(b)); }
constexpr bool any(Usage set, Usage bits) { return (uint32_t(set) & uint32_t(bits)) != 0; }
std::string usageName(Usage u);  // "sampled", "blend+image-load/store"
// The glMemoryBarrier bits a consumer touching a resource with `u` needs after an image store.
GLbitfield barrierBitsFor(Usage u);

// What kind of work a pass is: what its floor is measured against and how reports label it.
enum class PassKind { Raster, Compute, Cuda };
const char* passKindName(PassKind kind);

struct ResourceId {
    int version = -1;  // index into the graph's version table
    bool valid() const { return version >= 0; }
};

class FrameGraph;
class TexturePool;

class PassBuilder {
public:
    // A new transient texture, written by this pass as `how`.
    ResourceId create(const std::string& name, const TextureDesc& desc, Usage how);
    // A target the pass can do without (a G-buffer channel): allocated only when some live pass
    // reads it or it is an output; otherwise PassResources::texture() gives 0 and the writer skips it.
    ResourceId createIfRead(const std::string& name, const TextureDesc& desc, Usage how);
    ResourceId read(ResourceId id, Usage how);
    ResourceId read(const std::string& resourceName, Usage how);  // resolves at compile time to the last version
    ResourceId write(ResourceId id, Usage how);                   // read-modify-write: returns the new version
    void sideEffect();                                            // never culled (presents, readbacks)
    // Work the pass needs done before it runs, outside its timing window (a buffer upload): run at
    // the start of execute(), before the first pass's timer begins, when the pass is live and enabled.
    void beforeFrame(std::function<void()> prepare);

private:
    friend class FrameGraph;
    PassBuilder(FrameGraph& g, int pass) : graph_(g), pass_(pass) {}
    FrameGraph& graph_;
    int pass_;
};

class PassResources {
public:
    // The texture of a resource this pass declared (any version of it); throws lp::Error naming the
    // pass and the resource for one it did not declare, so a pass cannot reach around the graph.
    GLuint texture(ResourceId id) const;
    // The same for a buffer (importBuffer); each throws for the other kind.
    GLuint buffer(ResourceId id) const;
    const TextureDesc& desc(ResourceId id) const;
    // How the pass binds a texture it declared for image load/store (glBindImageTexture): the texture
    // and format, which for an sRGB texture are a view of it as its linear twin (image units take no
    // sRGB format; the shader stores the encoding itself). texture 0 when the resource has none.
    struct ImageBinding {
        GLuint texture = 0;
        GLenum format = 0;
    };
    ImageBinding image(ResourceId id) const;
    // The timer ring of this execute (null when untimed): passes timed outside GL (CUDA events)
    // report through GpuTimerRing::addExternal.
    gl::GpuTimerRing* timers() const { return timers_; }

private:
    friend class FrameGraph;
    PassResources(const FrameGraph& g, int pass, gl::GpuTimerRing* timers) : graph_(g), pass_(pass), timers_(timers) {}
    GLuint object(ResourceId id, bool buffer) const;
    const FrameGraph& graph_;
    int pass_ = -1;
    gl::GpuTimerRing* timers_ = nullptr;
};

using SetupFn = std::function<void(PassBuilder&)>;
using ExecuteFn = std::function<void(const PassResources&)>;

struct PassReport {
    std::string name;
    PassKind kind = PassKind::Compute;
    bool culled = false;
    bool disabled = false;            // switched off by the user
    std::string reason;               // why it was culled or disabled
    std::vector<std::string> reads;   // "gbuffer.normal", "hdr@1" for later versions
    std::vector<std::string> writes;
    GLbitfield barrierBefore = 0;     // glMemoryBarrier bits the graph issues before it runs
};

struct ResourceReport {
    std::string name;
    TextureDesc desc;
    bool imported = false;
    bool live = false;
    int firstPass = -1, lastPass = -1;  // in execution order
    bool buffer = false;                // importBuffer: a GL buffer (desc unused)
};

// One candidate pass of a frame: it runs, or why not (culled, disabled, or skipped by the builder).
struct PassDecision {
    std::string name;
    bool runs = false;
    std::string reason;  // "skipped: scene has no shadow-casting light"; empty when it runs
    std::vector<std::string> notes;  // what the pass recorded about its work (notePass)
};

class FrameGraph {
public:
    // Runs `setup` now; `execute` runs in execute() if the pass survives compile().
    void addPass(const std::string& name, PassKind kind, const SetupFn& setup, ExecuteFn execute);
    // Frostbite-style: setup fills a Data struct (the handles it declared) that execute receives.
    template <typename Data>
    const Data& addPass(const std::string& name, PassKind kind, const std::function<void(PassBuilder&, Data&)>& setup,
                        std::function<void(const Data&, const PassResources&)> execute) {
        auto data = std::make_shared<Data>();
        addPass(
            name, kind, [&](PassBuilder& b) { setup(b, *data); },
            [data, execute = std::move(execute)](const PassResources& r) { execute(*data, r); });
        return *data;
    }
    // A texture that lives outside the graph (not pooled, not in liveTransientBytes).
    ResourceId importTexture(const std::string& name, const TextureDesc& desc, GLuint texture);
    // The same for a texture that only exists once an earlier pass made it (an environment cube the
    // bake pass makes): `texture` is asked each time a pass asks for it during execute().
    ResourceId importTexture(const std::string& name, const TextureDesc& desc, std::function<GLuint()> texture);
    // A buffer that lives outside the graph, such as one a pass refills each frame (gl::StreamBuffer):
    // passes declare how they write it (an upload: Usage::Transfer) and read it (StorageBuffer), so
    // the graph orders its readers after its writer and a pass touches it only if it declared it.
    // `buffer` is asked each time a pass asks for it (a refill may change it). An upload (Transfer)
    // GL orders with later reads by itself; a shader's storage writes (StorageBuffer, the skinning
    // pass's posed vertices) are incoherent, so its readers get the barrier bits of how they read
    // (storage block, vertex attributes, copies), and the writer one against the reads since the last
    // barrier (the previous frame's draws). A disabled writer passes its input through, as for
    // textures: readers get the version before it.
    ResourceId importBuffer(const std::string& name, std::function<GLuint()> buffer);
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
    // A line about the work an added pass will do ("cascade 0: 12 draws, 40960 of 282k triangles"),
    // shown under it by explainText(); notes of names never added are ignored.
    void notePass(const std::string& passName, const std::string& note);
    // Every candidate pass (added or skipped) with its decision, in the order they were considered;
    // after compile(). explainText() is what 'lightpass graph --explain' prints.
    std::vector<PassDecision> explain() const;
    std::string explainText() const;
    // Bytes of the live transient textures (before the pool reuses memory between lifetimes).
    size_t liveTransientBytes() const;

    // Throws lp::Error for a read of a resource nothing writes, a double write of one version,
    // a cycle, or a graph with no output.
    void compile();
    // Allocates transient textures from the pool, records every live pass in order with the
    // barriers compile() derived, and releases textures after their last use so later passes can
    // reuse them. With the state check on, throws lp::Error naming a pass that leaves the watched GL
    // state (engine/gl/state_check.hpp) other than it found it.
    void execute(TexturePool& pool, gl::GpuTimerRing* timers = nullptr);
    // The per-pass GL state check: from LIGHTPASS_GL_STATE_CHECKS (off unless it is 1) until set here.
    void setStateChecks(bool on) { stateChecks_ = on; }
    bool stateChecks() const { return stateChecks_; }

    const std::vector<PassReport>& report() const { return report_; }
    // glMemoryBarrier bits issued before a pass (0 when none, or no such live pass), and after the
    // last pass for the outputs (what the application then reads, blits or samples); after compile().
    GLbitfield barriersBefore(const std::string& passName) const;
    GLbitfield barriersAfterFrame() const { return finalBarrier_; }
    PassKind passKind(const std::string& passName) const;  // Compute for an unknown name
    std::vector<std::string> executionOrder() const;
    std::vector<ResourceReport> resources() const;
    bool isLive(const std::string& passName) const;
    // Bytes a pass must move at least: every texel of what it reads plus what it writes (an
    // in-place write counts as a read and a write). The basis of its bandwidth floor. Imported
    // textures (environment cubes, LUTs) are looked up by direction, not streamed: not counted.
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
        std::function<GLuint()> importedLater;  // importTexture's lazy form
        bool isImported = false;
        std::vector<int> versions;
        GLuint texture = 0;  // bound during execute
        int first = -1, last = -1;
        bool live = false;
        bool output = false;
        bool optional = false;  // createIfRead: dropped when nothing live reads it
        bool cuda = false;      // a live pass touches it with Usage::Cuda (the pool may share it)
        bool buffer = false;    // importBuffer: a GL buffer, not a texture
    };
    struct Version {
        int resource = -1;
        int number = 0;
        int writer = -1;  // pass index; -1 for v0 of an imported resource
        std::vector<int> readers;
    };
    struct NamedRead {
        std::string name;
        Usage how;
    };
    struct Pass {
        std::string name;
        PassKind kind = PassKind::Compute;
        ExecuteFn execute;
        std::function<void()> beforeFrame;  // PassBuilder::beforeFrame
        std::vector<int> reads;  // version indices
        std::vector<Usage> readUsage;  // parallel to reads
        std::vector<NamedRead> namedReads;  // resolved in compile
        std::vector<int> writes;
        std::vector<Usage> writeUsage;  // parallel to writes
        bool sideEffect = false;
        bool live = false;
        bool disabled = false;
        GLbitfield barrierBefore = 0;
    };
    int newVersion(int resource, int writer);
    void addRead(int pass, int version, Usage how);
    void checkUsage(int pass, int version, Usage how, bool write) const;
    // compile()'s phases, in order.
    void resolveNamedReads();
    void applyDisabledPasses();
    void validateReads() const;
    std::vector<int> findLivePasses();
    void orderPasses(size_t liveCount);
    void assignLifetimes();
    void planBarriers();
    void buildReport();
    bool declares(int pass, int resource) const;
    std::string versionName(int version) const;
    const Resource& resourceOf(ResourceId id) const;

    std::vector<Resource> resources_;
    std::vector<Version> versions_;
    std::vector<Pass> passes_;
    int resolve(int version) const;  // follows pass-through aliases of disabled passes
    std::vector<std::pair<std::string, std::string>> skipped_;
    std::vector<std::pair<std::string, std::string>> notes_;  // (pass name, note) in the order noted
    std::vector<std::pair<bool, int>> candidates_;  // (added, index into passes_ or skipped_) in order
    std::vector<int> alias_;         // per version: the version it passes through to, or -1
    std::vector<int> outputs_;
    std::vector<std::string> namedOutputs_;
    std::vector<int> order_;
    std::vector<PassReport> report_;
    TexturePool* pool_ = nullptr;  // during execute(): where PassResources::image finds views
    GLbitfield finalBarrier_ = 0;
    bool compiled_ = false;
    bool stateChecks_ = gl::stateChecksFromEnvironment();
};

}  // namespace lp::fg
