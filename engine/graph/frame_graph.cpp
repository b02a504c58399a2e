#include "engine/graph/frame_graph.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <sstream>

#include "engine/core/error.hpp"
#include "engine/gl/gpu_timer.hpp"
#include "engine/gl/handles.hpp"
#include "engine/gl/state_check.hpp"
#include "engine/graph/texture_pool.hpp"

namespace lp::fg {

// ---- usages and kinds -------------------------------------------------------------------------

std::string usageName(Usage u) {
    static const std::pair<Usage, const char*> names[] = {
        {Usage::ImageLoadStore, "image-load/store"}, {Usage::Sampled, "sampled"},
        {Usage::ImageLoad, "image-load"},           {Usage::ImageStore, "image-store"},
        {Usage::ColorAttachment, "color"},          {Usage::Blend, "blend"},
        {Usage::DepthAttachment, "depth"},          {Usage::DepthTest, "depth-test"},
        {Usage::Transfer, "transfer"},              {Usage::Cuda, "cuda"},
        {Usage::StorageBuffer, "storage-buffer"},   {Usage::VertexBuffer, "vertex-buffer"}};
    std::string out;
    uint32_t left = uint32_t(u);
    for (const auto& [bits, name] : names) {
        if ((left & uint32_t(bits)) != uint32_t(bits)) continue;
        left &= ~uint32_t(bits);
        out += (out.empty() ? "" : "+") + std::string(name);
    }
    return out.empty() ? "none" : out;
}

GLbitfield barrierBitsFor(Usage u) {
    GLbitfield bits = 0;
    if (any(u, Usage::Sampled)) bits |= GL_TEXTURE_FETCH_BARRIER_BIT;
    if (any(u, Usage::ImageLoadStore)) bits |= GL_SHADER_IMAGE_ACCESS_BARRIER_BIT;
    if (any(u, Usage::ColorAttachment | Usage::Blend | Usage::DepthAttachment | Usage::DepthTest))
        bits |= GL_FRAMEBUFFER_BARRIER_BIT;
    if (any(u, Usage::Transfer)) bits |= GL_TEXTURE_UPDATE_BARRIER_BIT;
    if (any(u, Usage::StorageBuffer)) bits |= GL_SHADER_STORAGE_BARRIER_BIT;
    if (any(u, Usage::VertexBuffer)) bits |= GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT;
    // CUDA reads the texture's memory once mapped: every way GL may still hold image stores back.
    if (any(u, Usage::Cuda))
        bits |= GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT;
    return bits;
}

const char* passKindName(PassKind kind) {
    switch (kind) {
        case PassKind::Raster: return "raster";
        case PassKind::Compute: return "compute";
        case PassKind::Cuda: return "cuda";
    }
    return "compute";
}

// ---- building ---------------------------------------------------------------------------------

int FrameGraph::newVersion(int resource, int writer) {
    Version v;
    v.resource = resource;
    v.number = int(resources_[resource].versions.size());
    v.writer = writer;
    versions_.push_back(v);
    resources_[resource].versions.push_back(int(versions_.size()) - 1);
    return int(versions_.size()) - 1;
}

void FrameGraph::addRead(int pass, int version, Usage how) {
    passes_[pass].reads.push_back(version);
    passes_[pass].readUsage.push_back(how);
    versions_[version].readers.push_back(pass);
}

std::string FrameGraph::versionName(int version) const {
    const Version& v = versions_[version];
    const std::string& name = resources_[v.resource].name;
    return v.number == 0 ? name : name + "@" + std::to_string(v.number);
}

ResourceId PassBuilder::create(const std::string& name, const TextureDesc& desc, Usage how) {
    if (desc.width <= 0 || desc.height <= 0)
        throw Error("frame graph: pass '" + graph_.passes_[pass_].name + "' creates '" + name + "' with an empty size");
    FrameGraph::Resource r;
    r.name = name;
    r.desc = desc;
    graph_.resources_.push_back(r);
    int v = graph_.newVersion(int(graph_.resources_.size()) - 1, pass_);
    graph_.passes_[pass_].writes.push_back(v);
    graph_.passes_[pass_].writeUsage.push_back(how);
    return ResourceId{v};
}

ResourceId PassBuilder::createIfRead(const std::string& name, const TextureDesc& desc, Usage how) {
    ResourceId id = create(name, desc, how);
    graph_.resources_.back().optional = true;
    return id;
}

// A buffer is uploaded to (Transfer) or written by a shader (StorageBuffer), and read as a storage
// block, as vertex attributes or by a copy (Transfer); a texture is neither.
void FrameGraph::checkUsage(int pass, int version, Usage how, bool write) const {
    const Resource& r = resources_[versions_[version].resource];
    const Usage allowed = !r.buffer ? Usage(~uint32_t(Usage::StorageBuffer | Usage::VertexBuffer))
                          : write   ? Usage::Transfer | Usage::StorageBuffer
                                    : Usage::StorageBuffer | Usage::Transfer | Usage::VertexBuffer;
    if ((uint32_t(how) & ~uint32_t(allowed)) == 0) return;
    throw Error("frame graph: pass '" + passes_[pass].name + "' " + (write ? "writes " : "reads ") +
                (r.buffer ? "buffer '" : "texture '") + r.name + "' as " + usageName(how) + " (" +
                (!r.buffer ? "a texture is not a storage or vertex buffer"
                 : write   ? "a buffer is written by an upload or a shader: transfer or storage-buffer"
                           : "a buffer is read as storage-buffer, vertex-buffer or transfer") +
                ")");
}

ResourceId PassBuilder::read(ResourceId id, Usage how) {
    if (!id.valid() || id.version >= int(graph_.versions_.size()))
        throw Error("frame graph: pass '" + graph_.passes_[pass_].name + "' reads an invalid resource handle");
    graph_.checkUsage(pass_, id.version, how, false);
    graph_.addRead(pass_, id.version, how);
    return id;
}

ResourceId PassBuilder::read(const std::string& resourceName, Usage how) {
    graph_.passes_[pass_].namedReads.push_back({resourceName, how});
    return ResourceId{};
}

ResourceId PassBuilder::write(ResourceId id, Usage how) {
    auto& pass = graph_.passes_[pass_];
    if (!id.valid() || id.version >= int(graph_.versions_.size()))
        throw Error("frame graph: pass '" + pass.name + "' writes an invalid resource handle");
    const auto& v = graph_.versions_[id.version];
    const auto& res = graph_.resources_[v.resource];
    if (res.versions.back() != id.version)
        throw Error("frame graph: pass '" + pass.name + "' writes '" + graph_.versionName(id.version) +
                    "', which pass '" + graph_.passes_[graph_.versions_[res.versions[v.number + 1]].writer].name +
                    "' already wrote (a version is written once)");
    graph_.checkUsage(pass_, id.version, how, true);
    // Writing in place reads the previous contents, the same way it writes them.
    graph_.addRead(pass_, id.version, how);
    int nv = graph_.newVersion(v.resource, pass_);
    graph_.passes_[pass_].writes.push_back(nv);
    graph_.passes_[pass_].writeUsage.push_back(how);
    return ResourceId{nv};
}

void PassBuilder::sideEffect() { graph_.passes_[pass_].sideEffect = true; }

void PassBuilder::beforeFrame(std::function<void()> prepare) { graph_.passes_[pass_].beforeFrame = std::move(prepare); }

void FrameGraph::addPass(const std::string& name, PassKind kind, const SetupFn& setup, ExecuteFn execute) {
    for (const auto& p : passes_)
        if (p.name == name) throw Error("frame graph: two passes named '" + name + "'");
    Pass pass;
    pass.name = name;
    pass.kind = kind;
    pass.execute = std::move(execute);
    passes_.push_back(std::move(pass));
    candidates_.emplace_back(true, int(passes_.size()) - 1);
    compiled_ = false;
    PassBuilder builder(*this, int(passes_.size()) - 1);
    if (setup) setup(builder);
}

ResourceId FrameGraph::importTexture(const std::string& name, const TextureDesc& desc, GLuint texture) {
    Resource r;
    r.name = name;
    r.desc = desc;
    r.imported = texture;
    r.isImported = true;
    resources_.push_back(r);
    return ResourceId{newVersion(int(resources_.size()) - 1, -1)};
}

ResourceId FrameGraph::importTexture(const std::string& name, const TextureDesc& desc, std::function<GLuint()> texture) {
    ResourceId id = importTexture(name, desc, GLuint(0));
    resources_.back().importedLater = std::move(texture);
    return id;
}

ResourceId FrameGraph::importBuffer(const std::string& name, std::function<GLuint()> buffer) {
    ResourceId id = importTexture(name, TextureDesc{}, std::move(buffer));
    resources_.back().buffer = true;
    return id;
}

void FrameGraph::disablePass(const std::string& passName) {
    for (auto& p : passes_)
        if (p.name == passName) p.disabled = true;
    compiled_ = false;
}

void FrameGraph::notePass(const std::string& passName, const std::string& note) { notes_.emplace_back(passName, note); }

void FrameGraph::skipPass(const std::string& passName, const std::string& reason) {
    skipped_.emplace_back(passName, reason);
    candidates_.emplace_back(false, int(skipped_.size()) - 1);
}

int FrameGraph::resolve(int version) const {
    while (version >= 0 && version < int(alias_.size()) && alias_[version] >= 0) version = alias_[version];
    return version;
}

void FrameGraph::markOutput(ResourceId id) {
    if (!id.valid()) throw Error("frame graph: output is an invalid resource handle");
    outputs_.push_back(id.version);
}
void FrameGraph::markOutput(const std::string& resourceName) { namedOutputs_.push_back(resourceName); }

// ---- compiling --------------------------------------------------------------------------------

namespace {
int findResource(const std::vector<std::string>& names, const std::string& name) {
    for (int i = int(names.size()) - 1; i >= 0; --i)
        if (names[i] == name) return i;
    return -1;
}
}  // namespace

void FrameGraph::compile() {
    resolveNamedReads();
    applyDisabledPasses();
    validateReads();
    const std::vector<int> live = findLivePasses();
    orderPasses(live.size());
    assignLifetimes();
    planBarriers();
    buildReport();
    compiled_ = true;
}

// Names ("gbuffer.depth") become the last version of that resource, outputs included.
void FrameGraph::resolveNamedReads() {
    std::vector<std::string> names;
    for (const auto& r : resources_) names.push_back(r.name);
    auto lastVersion = [&](const std::string& name, const std::string& who) {
        int r = findResource(names, name);
        if (r < 0) throw Error("frame graph: " + who + " reads '" + name + "', which no pass creates or imports");
        return resources_[r].versions.back();
    };
    for (int pi = 0; pi < int(passes_.size()); ++pi) {
        Pass& p = passes_[pi];
        std::vector<NamedRead> named;
        named.swap(p.namedReads);
        for (const NamedRead& read : named) {
            int v = lastVersion(read.name, "pass '" + p.name + "'");
            if (versions_[v].writer == pi)
                throw Error("frame graph: pass '" + p.name + "' reads '" + read.name + "', which only it writes");
            checkUsage(pi, v, read.how, false);
            addRead(pi, v, read.how);
        }
    }
    for (const auto& name : namedOutputs_) outputs_.push_back(lastVersion(name, "the output"));
    namedOutputs_.clear();
    if (outputs_.empty()) throw Error("frame graph: no output marked; nothing would be drawn");
}

// Disabled passes: in-place writes become aliases of their input; created textures get cleared.
void FrameGraph::applyDisabledPasses() {
    alias_.assign(versions_.size(), -1);
    for (int pi = 0; pi < int(passes_.size()); ++pi) {
        Pass& p = passes_[pi];
        if (!p.disabled) continue;
        for (int w : p.writes) {
            const Version& wv = versions_[w];
            if (wv.number > 0) alias_[w] = resources_[wv.resource].versions[wv.number - 1];
        }
        for (int r : p.reads) {
            auto& readers = versions_[r].readers;
            readers.erase(std::remove(readers.begin(), readers.end(), pi), readers.end());
        }
        p.reads.clear();
        p.readUsage.clear();
        std::vector<int> created;
        for (int w : p.writes)
            if (versions_[w].number == 0) created.push_back(w);
        p.writes = created;
        p.writeUsage.assign(created.size(), Usage::Transfer);
        if (created.empty()) {
            p.execute = nullptr;
            continue;
        }
        p.kind = PassKind::Compute;  // a clear moves bytes; no raster work is left
        p.execute = [this, created](const PassResources&) {
            const uint32_t zero[4] = {0, 0, 0, 0};  // 0.0f, 0u and a zero depth/stencil alike
            for (int v : created) {
                const Resource& r = resources_[versions_[v].resource];
                if (!r.texture) continue;  // an optional target nothing reads
                const gl::ClearFormat f = gl::clearFormatFor(r.desc.format);
                for (int level = 0; level < r.desc.levels; ++level)
                    glClearTexImage(r.texture, level, f.format, f.type, zero);
            }
        };
    }
    for (int pi = 0; pi < int(passes_.size()); ++pi)
        for (int& r : passes_[pi].reads) {
            int to = resolve(r);
            if (to != r) {
                versions_[to].readers.push_back(pi);
                r = to;
            }
        }
    for (int& v : outputs_) v = resolve(v);
}

void FrameGraph::validateReads() const {
    for (const auto& p : passes_)
        for (int v : p.reads)
            if (versions_[v].writer < 0 && !resources_[versions_[v].resource].isImported)
                throw Error("frame graph: pass '" + p.name + "' reads '" + versionName(v) + "', which nothing writes");
}

// Liveness: walk back from the outputs (and side effects). Returns the live passes.
std::vector<int> FrameGraph::findLivePasses() {
    for (auto& p : passes_) p.live = false;
    for (auto& r : resources_) {
        r.live = false;
        r.output = false;
        r.first = r.last = -1;
    }
    std::vector<char> needed(versions_.size(), 0);
    std::vector<int> work;
    auto need = [&](int v) {
        if (!needed[v]) {
            needed[v] = 1;
            work.push_back(v);
        }
    };
    std::vector<int> livePasses;
    auto makeLive = [&](int pi) {
        if (passes_[pi].live) return;
        passes_[pi].live = true;
        livePasses.push_back(pi);
        for (int r : passes_[pi].reads) need(r);
        for (int w : passes_[pi].writes) {
            const Version& wv = versions_[w];
            if (wv.number > 0) need(resolve(resources_[wv.resource].versions[wv.number - 1]));
        }
    };
    for (int v : outputs_) {
        need(v);
        resources_[versions_[v].resource].output = true;
    }
    for (size_t i = 0; i < passes_.size(); ++i)
        if (passes_[i].sideEffect) makeLive(int(i));
    while (!work.empty()) {
        int v = work.back();
        work.pop_back();
        if (versions_[v].writer >= 0) makeLive(versions_[v].writer);
    }
    return livePasses;
}

// Order the live passes: read-after-write, write-after-write and write-after-read edges;
// among ready passes the one added first goes first, so the order is stable and readable.
void FrameGraph::orderPasses(size_t liveCount) {
    const int n = int(passes_.size());
    std::vector<std::set<int>> succ(n);
    std::vector<int> indeg(n, 0);
    auto edge = [&](int from, int to) {
        if (from < 0 || from == to || !passes_[from].live || !passes_[to].live) return;
        if (succ[from].insert(to).second) ++indeg[to];
    };
    for (int pi = 0; pi < n; ++pi) {
        if (!passes_[pi].live) continue;
        for (int r : passes_[pi].reads) edge(versions_[r].writer, pi);
        for (int w : passes_[pi].writes) {
            const Version& wv = versions_[w];
            if (wv.number == 0) continue;
            int prev = resolve(resources_[wv.resource].versions[wv.number - 1]);
            edge(versions_[prev].writer, pi);
            for (int reader : versions_[prev].readers) edge(reader, pi);
        }
    }
    order_.clear();
    std::set<int> ready;
    for (int pi = 0; pi < n; ++pi)
        if (passes_[pi].live && indeg[pi] == 0) ready.insert(pi);
    while (!ready.empty()) {
        int pi = *ready.begin();
        ready.erase(ready.begin());
        order_.push_back(pi);
        for (int s : succ[pi])
            if (--indeg[s] == 0) ready.insert(s);
    }
    if (order_.size() != liveCount) {
        std::string cycle;
        for (int pi = 0; pi < n; ++pi)
            if (passes_[pi].live && indeg[pi] > 0) cycle += (cycle.empty() ? "" : ", ") + passes_[pi].name;
        throw Error("frame graph: cycle between passes " + cycle);
    }
}

// Lifetimes in execution order; optional targets nobody live reads are not allocated (their
// writer sees texture 0).
void FrameGraph::assignLifetimes() {
    std::vector<char> readByLive(resources_.size(), 0);
    for (const Version& v : versions_)
        for (int reader : v.readers)
            if (passes_[reader].live) readByLive[v.resource] = 1;
    for (int i = 0; i < int(order_.size()); ++i) {
        const Pass& p = passes_[order_[i]];
        auto touch = [&](int v, Usage how) {
            Resource& r = resources_[versions_[v].resource];
            if (r.optional && !r.output && !readByLive[versions_[v].resource]) return;
            r.live = true;
            r.cuda = r.cuda || any(how, Usage::Cuda);
            if (r.first < 0) r.first = i;
            r.last = std::max(r.last, i);
        };
        for (size_t k = 0; k < p.reads.size(); ++k) touch(p.reads[k], p.readUsage[k]);
        for (size_t k = 0; k < p.writes.size(); ++k) touch(p.writes[k], p.writeUsage[k]);
    }
    for (auto& r : resources_)
        if (r.output && r.live) r.last = int(order_.size());
}

// Barriers from the declared usages. A resource written with an image store stays "dirty" until a
// barrier with the bits of each later usage was issued; glMemoryBarrier is global, so one barrier
// before a pass covers every dirty resource. Everything else (attachments, clears, CUDA's map and
// unmap) GL orders by itself. After the last pass, the outputs get the bits of whatever the
// application does with them (readback, blit, sampling).
//
// Image stores are incoherent in the other direction too (write after read): a GPU may start a
// dispatch that image-stores a texture while an earlier command still reads it (NVIDIA overlaps
// consecutive dispatches), so a pass that image-stores a texture gets a barrier when a command since
// the last barrier may have read that texture: the resource itself (read by a shader since; an
// imported one, such as a history, by the previous frame), or, for a transient's first write, any
// texture the pool may hand out again that was released since (the pool aliases transients; at the
// start of the frame the previous frame released them all). Measured on an H100: without it the visibility resolve rewrote the G-buffer
// while the previous frame's tiled lights were still reading it.
void FrameGraph::planBarriers() {
    std::vector<char> dirty(resources_.size(), 0);
    std::vector<GLbitfield> covered(resources_.size(), 0);
    std::vector<char> readSinceBarrier(resources_.size(), 0);
    for (size_t r = 0; r < resources_.size(); ++r) readSinceBarrier[r] = resources_[r].isImported;  // last frame's
    std::vector<char> writtenThisFrame(resources_.size(), 0);
    bool releasedSinceBarrier = true;                           // the previous frame released all
    auto issue = [&](GLbitfield bits) {
        if (!bits) return;
        for (size_t r = 0; r < resources_.size(); ++r) {
            if (dirty[r]) covered[r] |= bits;
            readSinceBarrier[r] = 0;
        }
        releasedSinceBarrier = false;
    };
    for (auto& p : passes_) p.barrierBefore = 0;
    for (int i = 0; i < int(order_.size()); ++i) {
        Pass& p = passes_[order_[i]];
        GLbitfield bits = 0;
        auto need = [&](int version, Usage how) {
            const int r = versions_[version].resource;
            // A copy out of a buffer that a shader wrote waits for buffer updates, not texture ones.
            const GLbitfield want = resources_[r].buffer && any(how, Usage::Transfer)
                                        ? (barrierBitsFor(how) & ~GLbitfield(GL_TEXTURE_UPDATE_BARRIER_BIT)) | GL_BUFFER_UPDATE_BARRIER_BIT
                                        : barrierBitsFor(how);
            if (dirty[r]) bits |= want & ~covered[r];
        };
        for (size_t k = 0; k < p.reads.size(); ++k) need(p.reads[k], p.readUsage[k]);
        for (size_t k = 0; k < p.writes.size(); ++k) need(p.writes[k], p.writeUsage[k]);
        for (size_t k = 0; k < p.writes.size(); ++k) {
            const int r = versions_[p.writes[k]].resource;
            // A shader writing a buffer that commands since the last barrier may still read (an
            // imported one: the previous frame's draws).
            if (resources_[r].buffer && any(p.writeUsage[k], Usage::StorageBuffer) && readSinceBarrier[r])
                bits |= GL_SHADER_STORAGE_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT;
            if (!any(p.writeUsage[k], Usage::ImageStore)) continue;
            const bool fresh = !writtenThisFrame[r] && !resources_[r].isImported;
            if (readSinceBarrier[r] || (fresh && releasedSinceBarrier)) bits |= GL_SHADER_IMAGE_ACCESS_BARRIER_BIT;
        }
        p.barrierBefore = bits;
        issue(bits);
        // Shader reads (texture fetches, image loads); fixed-function ones GL orders itself.
        for (size_t k = 0; k < p.reads.size(); ++k)
            if (any(p.readUsage[k], Usage::Sampled | Usage::ImageLoad)) readSinceBarrier[versions_[p.reads[k]].resource] = 1;
        for (size_t k = 0; k < p.writes.size(); ++k) {
            const int r = versions_[p.writes[k]].resource;
            dirty[r] = any(p.writeUsage[k], Usage::ImageStore) || (resources_[r].buffer && any(p.writeUsage[k], Usage::StorageBuffer));
            covered[r] = 0;
            writtenThisFrame[r] = 1;
            if (any(p.writeUsage[k], Usage::Sampled | Usage::ImageLoad)) readSinceBarrier[r] = 1;
        }
        for (size_t r = 0; r < resources_.size(); ++r)
            if (resources_[r].live && resources_[r].last == i && !resources_[r].isImported) releasedSinceBarrier = true;
    }
    finalBarrier_ = 0;
    const GLbitfield external = GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                                GL_FRAMEBUFFER_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT;
    for (int v : outputs_) {
        const int r = versions_[v].resource;
        if (dirty[r]) finalBarrier_ |= external & ~covered[r];
    }
}

void FrameGraph::buildReport() {
    report_.clear();
    for (const auto& p : passes_) {
        PassReport rep;
        rep.name = p.name;
        rep.kind = p.kind;
        rep.culled = !p.live;
        rep.barrierBefore = p.live ? p.barrierBefore : 0;
        for (int v : p.reads) {
            bool inPlace = false;
            for (int w : p.writes)
                if (versions_[w].resource == versions_[v].resource) inPlace = true;
            if (!inPlace) rep.reads.push_back(versionName(v));
        }
        for (int v : p.writes) rep.writes.push_back(versionName(v));
        rep.disabled = p.disabled;
        if (p.disabled) {
            rep.reason = p.writes.empty() ? "disabled by the user (its input passes through)"
                                          : "disabled by the user (its outputs are cleared)";
            rep.culled = !p.live;
        }
        if (!p.live && !p.disabled) {
            std::string list;
            for (const auto& w : rep.writes) list += (list.empty() ? "" : ", ") + w;
            rep.reason = p.writes.empty() ? "writes nothing and has no side effect"
                                          : "culled: nothing live reads its writes (" + list + ")";
        }
        report_.push_back(rep);
    }
}

// ---- executing --------------------------------------------------------------------------------

std::vector<PassDecision> FrameGraph::explain() const {
    std::vector<PassDecision> out;
    for (const auto& [added, index] : candidates_) {
        if (!added) {
            out.push_back({skipped_[size_t(index)].first, false, "skipped: " + skipped_[size_t(index)].second, {}});
            continue;
        }
        const Pass& p = passes_[size_t(index)];
        PassDecision d{p.name, p.live && !p.disabled, "", {}};
        if (index < int(report_.size()) && !d.runs) d.reason = report_[size_t(index)].reason;
        if (p.disabled && p.live) d.reason = report_[size_t(index)].reason;  // runs as a clear / pass-through
        for (const auto& [name, note] : notes_)
            if (name == p.name) d.notes.push_back(note);
        out.push_back(d);
    }
    return out;
}

std::string FrameGraph::explainText() const {
    std::ostringstream out;
    out << "candidate passes:\n";
    for (const PassDecision& d : explain()) {
        out << "  " << (d.runs ? "runs     " : "-        ") << d.name << (d.reason.empty() ? "" : "  (" + d.reason + ")")
            << "\n";
        for (const std::string& note : d.notes) out << "             " << note << "\n";
    }
    return out.str();
}

size_t FrameGraph::liveTransientBytes() const {
    size_t total = 0;
    for (const auto& r : resources_)
        if (r.live && !r.isImported) total += r.desc.bytes();
    return total;
}

bool FrameGraph::declares(int pass, int resource) const {
    const Pass& p = passes_[size_t(pass)];
    for (int v : p.reads)
        if (versions_[v].resource == resource) return true;
    for (int v : p.writes)
        if (versions_[v].resource == resource) return true;
    return false;
}

GLuint PassResources::object(ResourceId id, bool buffer) const {
    const auto& r = graph_.resourceOf(id);
    const int resource = graph_.versions_[id.version].resource;
    // A disabled pass's reads are dropped, so only the passes that run are held to their declarations.
    if (pass_ >= 0 && !graph_.declares(pass_, resource) && !graph_.passes_[size_t(pass_)].disabled)
        throw Error("frame graph: pass '" + graph_.passes_[size_t(pass_)].name + "' uses '" + r.name +
                    "', which it did not declare (declare it with read() or write() in its setup)");
    if (r.buffer != buffer)
        throw Error("frame graph: pass '" + (pass_ >= 0 ? graph_.passes_[size_t(pass_)].name : std::string("?")) +
                    "' asks for '" + r.name + "' as a " + (buffer ? "buffer" : "texture") + ", but it is a " +
                    (r.buffer ? "buffer" : "texture"));
    if (r.importedLater) return r.importedLater();
    return r.texture;
}
GLuint PassResources::texture(ResourceId id) const { return object(id, false); }
GLuint PassResources::buffer(ResourceId id) const { return object(id, true); }
const TextureDesc& PassResources::desc(ResourceId id) const { return graph_.resourceOf(id).desc; }

PassResources::ImageBinding PassResources::image(ResourceId id) const {
    const GLuint tex = texture(id);
    const GLenum format = desc(id).format, imageFormat = gl::imageFormatOf(format);
    if (!tex || imageFormat == format) return {tex, format};
    const GLuint view = graph_.pool_ && !graph_.resourceOf(id).isImported ? graph_.pool_->imageTexture(tex) : 0;
    if (!view)
        throw Error("frame graph: pass '" + graph_.passes_[size_t(pass_)].name + "' stores into '" +
                    graph_.resourceOf(id).name + "' (" + gl::formatName(format) +
                    ") as an image, which needs a view only the graph's own textures have");
    return {view, imageFormat};
}

const FrameGraph::Resource& FrameGraph::resourceOf(ResourceId id) const {
    if (!id.valid() || id.version >= int(versions_.size())) throw Error("frame graph: invalid resource handle");
    return resources_[versions_[id.version].resource];
}

void FrameGraph::execute(TexturePool& pool, gl::GpuTimerRing* timers) {
    if (!compiled_) compile();
    const gl::WatchedState before = stateChecks_ ? gl::captureWatchedState() : gl::WatchedState{};
    pool.beginFrame();
    pool_ = &pool;
    for (int i : order_) {
        const Pass& p = passes_[i];
        if (p.beforeFrame && !p.disabled) {
            gl::DebugGroup group(p.name + " (before the frame)");
            p.beforeFrame();
            gl::checkErrors("pass '" + p.name + "' before the frame");
        }
    }
    for (auto& r : resources_) r.texture = r.isImported ? r.imported : 0;
    for (int i = 0; i < int(order_.size()); ++i) {
        for (auto& r : resources_)
            if (r.live && !r.isImported && r.first == i) r.texture = pool.acquire(r.desc, r.name, r.cuda);
        Pass& p = passes_[order_[i]];
        {
            gl::DebugGroup group(p.name);
            if (p.barrierBefore) glMemoryBarrier(p.barrierBefore);
            if (timers) timers->beginPass(p.name);
            if (p.execute) p.execute(PassResources(*this, order_[i], timers));
            if (timers) timers->endPass();
        }
        gl::checkErrors("pass '" + p.name + "'");
        if (stateChecks_) {
            const std::string changed = gl::describeStateChange(before, gl::captureWatchedState());
            if (!changed.empty()) throw Error("frame graph: pass '" + p.name + "' left GL state changed: " + changed);
        }
        for (auto& r : resources_)
            if (r.live && !r.isImported && r.last == i) pool.release(r.texture);
    }
    if (finalBarrier_) glMemoryBarrier(finalBarrier_);
    pool_ = nullptr;
    pool.endFrame();
}

// ---- reporting --------------------------------------------------------------------------------

std::vector<std::string> FrameGraph::executionOrder() const {
    std::vector<std::string> out;
    for (int pi : order_) out.push_back(passes_[pi].name);
    return out;
}

std::vector<ResourceReport> FrameGraph::resources() const {
    std::vector<ResourceReport> out;
    for (const auto& r : resources_) out.push_back({r.name, r.desc, r.isImported, r.live, r.first, r.last, r.buffer});
    return out;
}

bool FrameGraph::isLive(const std::string& passName) const {
    for (const auto& p : passes_)
        if (p.name == passName) return p.live;
    return false;
}

size_t FrameGraph::passTrafficBytes(const std::string& passName) const {
    for (const auto& p : passes_) {
        if (p.name != passName) continue;
        size_t bytes = 0;
        auto add = [&](int v) {
            const Resource& r = resources_[versions_[v].resource];
            if (!r.isImported) bytes += r.desc.bytes();
        };
        for (int v : p.reads) add(v);
        for (int v : p.writes) add(v);
        return bytes;
    }
    return 0;
}

GLbitfield FrameGraph::barriersBefore(const std::string& passName) const {
    for (const auto& p : passes_)
        if (p.name == passName) return p.live ? p.barrierBefore : 0;
    return 0;
}

PassKind FrameGraph::passKind(const std::string& passName) const {
    for (const auto& p : passes_)
        if (p.name == passName) return p.kind;
    return PassKind::Compute;
}

bool FrameGraph::hasPass(const std::string& passName) const {
    for (const auto& p : passes_)
        if (p.name == passName) return true;
    return false;
}

GLuint FrameGraph::outputTexture(const std::string& resourceName) const {
    for (int i = int(resources_.size()) - 1; i >= 0; --i)
        if (resources_[i].name == resourceName)
            return !resources_[i].live ? 0 : resources_[i].importedLater ? resources_[i].importedLater() : resources_[i].texture;
    return 0;
}
// A lazily imported texture (importTexture's function form, e.g. a history kept across frames) is
// asked for its texture, as passes do.
GLuint FrameGraph::outputTexture(ResourceId id) const {
    const auto& r = resourceOf(id);
    return r.importedLater ? r.importedLater() : r.texture;
}

namespace {
std::string join(const std::vector<std::string>& v) {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
    return s.empty() ? "-" : s;
}
std::string barrierText(GLbitfield bits) {
    static const std::pair<GLbitfield, const char*> names[] = {
        {GL_TEXTURE_FETCH_BARRIER_BIT, "texture-fetch"}, {GL_SHADER_IMAGE_ACCESS_BARRIER_BIT, "image-access"},
        {GL_FRAMEBUFFER_BARRIER_BIT, "framebuffer"},     {GL_TEXTURE_UPDATE_BARRIER_BIT, "texture-update"},
        {GL_PIXEL_BUFFER_BARRIER_BIT, "pixel-buffer"},   {GL_SHADER_STORAGE_BARRIER_BIT, "shader-storage"},
        {GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT, "vertex-attrib"}, {GL_BUFFER_UPDATE_BARRIER_BIT, "buffer-update"}};
    std::string out;
    for (const auto& [bit, name] : names)
        if (bits & bit) out += (out.empty() ? "" : " | ") + std::string(name);
    return out;
}
std::string descText(const TextureDesc& d) {
    std::ostringstream s;
    s << d.width << "x" << d.height << (d.cube ? " cube " : " ") << gl::formatName(d.format);
    if (d.levels > 1) s << " (" << d.levels << " mips)";
    return s.str();
}
}  // namespace

std::string FrameGraph::describe() const {
    std::ostringstream out;
    out << "passes that run, in order:\n";
    int i = 0;
    for (int pi : order_) {
        const PassReport& r = report_[pi];
        out << "  " << ++i << ". " << r.name << "  [" << passKindName(r.kind) << "]\n";
        if (r.barrierBefore) out << "      barrier: " << barrierText(r.barrierBefore) << "\n";
        out << "      reads:  " << join(r.reads) << "\n      writes: " << join(r.writes) << "\n";
    }
    if (finalBarrier_) out << "  then, for the outputs, barrier: " << barrierText(finalBarrier_) << "\n";
    bool any = false;
    for (const auto& r : report_) {
        if (!r.culled) continue;
        if (!any) out << "passes culled:\n";
        any = true;
        out << "  - " << r.name << ": " << r.reason << "\n";
    }
    if (!skipped_.empty()) {
        out << "passes not added (the scene or settings don't call for them):\n";
        for (const auto& [name, reason] : skipped_) out << "  - " << name << ": skipped: " << reason << "\n";
    }
    out << "transient textures:\n";
    size_t total = 0;
    for (const auto& r : resources_) {
        if (r.isImported) continue;
        out << "  " << r.name << "  " << descText(r.desc) << "  " << (r.live ? "" : "(not allocated)") << "\n";
        if (r.live) total += r.desc.bytes();
    }
    out << "  total " << (total / 1024.0 / 1024.0) << " MiB before pooling\n";
    return out.str();
}

std::string FrameGraph::toDot() const {
    std::ostringstream out;
    out << "digraph frame {\n  rankdir=LR;\n  node [fontname=\"Helvetica\"];\n";
    for (size_t pi = 0; pi < passes_.size(); ++pi) {
        const auto& p = passes_[pi];
        out << "  p" << pi << " [shape=box, style=" << (p.live ? "\"filled\", fillcolor=\"#cfe8ff\"" : "dashed")
            << ", label=\"" << p.name << "\\n" << passKindName(p.kind) << (p.live ? "" : " (culled)") << "\"];\n";
    }
    for (size_t ri = 0; ri < resources_.size(); ++ri) {
        const auto& r = resources_[ri];
        out << "  r" << ri << " [shape=ellipse, " << (r.live ? "" : "style=dashed, ") << "label=\"" << r.name << "\\n"
            << (r.buffer ? "buffer" : descText(r.desc)) << "\"];\n";
    }
    // Edges are labelled with the usage (one edge per pair; an in-place write shows as the write).
    std::map<std::pair<std::string, std::string>, Usage> edges;
    for (size_t pi = 0; pi < passes_.size(); ++pi) {
        const auto& p = passes_[pi];
        for (size_t i = 0; i < p.reads.size(); ++i)
            edges.emplace(std::make_pair("r" + std::to_string(versions_[p.reads[i]].resource), "p" + std::to_string(pi)),
                          p.readUsage[i]);
        for (size_t i = 0; i < p.writes.size(); ++i)
            edges.emplace(std::make_pair("p" + std::to_string(pi), "r" + std::to_string(versions_[p.writes[i]].resource)),
                          p.writeUsage[i]);
    }
    for (const auto& [ab, how] : edges)
        out << "  " << ab.first << " -> " << ab.second << " [label=\"" << usageName(how) << "\", fontsize=9];\n";
    out << "}\n";
    return out.str();
}

}  // namespace lp::fg
