#include "app/report_html.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "engine/core/error.hpp"

namespace lp::app {

namespace {
// The page's colours: the browser test (tests/cli/check_report.py) finds the graph, the bars and the
// plot by them, so they are named once here.
constexpr const char* kLiveBox = "#3b7dd8";
constexpr const char* kSkippedBox = "#d9d9d9";
constexpr const char* kTimeBar = "#e4572e";
constexpr const char* kFloorBar = "#2a9d8f";
constexpr const char* kFrontPoint = "#d62728";
constexpr const char* kOtherPoint = "#888888";

// Graph geometry (pixels).
constexpr double kArcArea = 230, kBoxWidth = 190, kBoxHeight = 22, kRowHeight = 30, kTop = 10;
// Timing bars.
constexpr double kBarLabel = 170, kBarArea = 560, kBarRow = 26;
// Sweep plot.
constexpr double kPlotWidth = 560, kPlotHeight = 320, kPlotMargin = 60, kPlotInset = 14;

std::string general(double v) {
    char b[64];
    std::snprintf(b, sizeof b, "%.3g", v);
    return b;
}

std::string num(double v, int digits = 3) {
    char b[64];
    std::snprintf(b, sizeof b, "%.*f", digits, v);
    return b;
}

std::string mib(size_t bytes) { return num(double(bytes) / 1048576.0, 2) + " MiB"; }

// The page's head: styles, and a recorder of script errors that the closing script reports in the
// title and in #page-errors (what a headless browser's --dump-dom reads back).
std::string pageHead(const std::string& title) {
    return "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>" + htmlEscape(title) +
           "</title>\n<style>\n"
           "body{font:14px/1.35 sans-serif;margin:16px;color:#222;background:#fff}\n"
           "h1{font-size:20px;margin:0 0 8px}h2{font-size:16px;margin:18px 0 6px}\n"
           "table.meta td{padding:1px 10px 1px 0;vertical-align:top}\n"
           "code{font:12px monospace;word-break:break-all}\n"
           ".views{display:flex;flex-wrap:wrap;gap:10px}\n"
           "figure{margin:0;border:1px solid #444;padding:4px;background:#f4f4f4}\n"
           "figure img{display:block}figcaption{font-size:12px;max-width:320px}\n"
           "table.res td,table.res th{padding:1px 8px;text-align:left;font-size:12px}\n"
           "svg text{font-family:sans-serif}\n"
           "</style>\n<script>\nwindow.pageErrors=[];\n"
           "window.addEventListener('error',function(e){window.pageErrors.push(String(e.message||"
           "(e.target&&e.target.src?'failed to load '+e.target.src.slice(0,40):'error')))},true);\n"
           "(function(){var c=console.error;console.error=function(){window.pageErrors.push(Array.prototype.join.call("
           "arguments,' '));c.apply(console,arguments)}})();\n</script>\n</head><body>\n";
}

// The closing script: every image must have decoded; the boxes of the elements marked data-check go
// into #page-layout as JSON (page coordinates), the errors into #page-errors, and the title ends with
// [page ok] or [page errors: N].
std::string pageTail() {
    return "<pre id=\"page-errors\" hidden></pre>\n<pre id=\"page-layout\" hidden></pre>\n<script>\n"
           "window.addEventListener('load',function(){\n"
           "document.querySelectorAll('img').forEach(function(i){if(!i.complete||!i.naturalWidth)"
           "window.pageErrors.push('image not decoded: '+(i.alt||'?'))});\n"
           "var out=[];document.querySelectorAll('[data-check]').forEach(function(e){var r=e.getBoundingClientRect();"
           "out.push({id:e.getAttribute('data-check'),x:r.left+window.scrollX,y:r.top+window.scrollY,w:r.width,h:r.height})});\n"
           "document.getElementById('page-layout').textContent=JSON.stringify(out);\n"
           "document.getElementById('page-errors').textContent=JSON.stringify(window.pageErrors);\n"
           "document.title+=window.pageErrors.length?' [page errors: '+window.pageErrors.length+']':' [page ok]';\n"
           "});\n</script>\n</body></html>\n";
}
}  // namespace

std::string htmlEscape(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&#39;"; break;
            default: out += c;
        }
    }
    return out;
}

std::string base64(const std::string& bytes) {
    static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    for (size_t i = 0; i < bytes.size(); i += 3) {
        const size_t n = std::min<size_t>(3, bytes.size() - i);
        uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
        if (n > 1) v |= uint32_t(uint8_t(bytes[i + 1])) << 8;
        if (n > 2) v |= uint32_t(uint8_t(bytes[i + 2]));
        out += alphabet[(v >> 18) & 63];
        out += alphabet[(v >> 12) & 63];
        out += n > 1 ? alphabet[(v >> 6) & 63] : '=';
        out += n > 2 ? alphabet[v & 63] : '=';
    }
    return out;
}

std::string pngDataUri(const std::string& pngBytes) { return "data:image/png;base64," + base64(pngBytes); }

std::string shellQuote(const std::string& argument) {
    if (!argument.empty() &&
        std::all_of(argument.begin(), argument.end(), [](unsigned char c) {
            return std::isalnum(c) || std::string("-_./=:,+@%").find(char(c)) != std::string::npos;
        }))
        return argument;
    std::string out = "'";
    for (char c : argument) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

std::string commandLine(const std::vector<std::string>& args) {
    std::string line = "lightpass";
    for (const auto& a : args) line += " " + shellQuote(a);
    return line;
}

Image8 shrinkToWidth(const Image8& image, int maxWidth) {
    if (image.width <= maxWidth || image.width <= 0) return image;
    Image8 out;
    out.width = maxWidth;
    out.height = std::max(1, int(std::lround(double(image.height) * maxWidth / image.width)));
    out.rgba.resize(size_t(out.width) * out.height * 4);
    for (int y = 0; y < out.height; ++y) {
        const int y0 = int(int64_t(y) * image.height / out.height);
        const int y1 = std::max(y0 + 1, int(int64_t(y + 1) * image.height / out.height));
        for (int x = 0; x < out.width; ++x) {
            const int x0 = int(int64_t(x) * image.width / out.width);
            const int x1 = std::max(x0 + 1, int(int64_t(x + 1) * image.width / out.width));
            uint32_t sum[4] = {0, 0, 0, 0};
            for (int sy = y0; sy < y1; ++sy)
                for (int sx = x0; sx < x1; ++sx)
                    for (int c = 0; c < 4; ++c) sum[c] += image.rgba[(size_t(sy) * image.width + sx) * 4 + c];
            const uint32_t count = uint32_t((y1 - y0) * (x1 - x0));
            for (int c = 0; c < 4; ++c)
                out.rgba[(size_t(y) * out.width + x) * 4 + c] = uint8_t((sum[c] + count / 2) / count);
        }
    }
    return out;
}

std::vector<ReportPass> passesInDrawingOrder(const std::vector<ReportPass>& candidates,
                                             const std::vector<std::string>& order) {
    // A sort key per pass: its place in the execution order, or, for one that does not run, just
    // after the last running candidate before it (several such keep their --explain order).
    std::vector<std::pair<double, size_t>> keys;
    std::vector<ReportPass> all = candidates;
    for (const auto& name : order)  // a pass that runs but is no candidate still gets its box
        if (std::none_of(all.begin(), all.end(), [&](const ReportPass& p) { return p.name == name; })) {
            ReportPass p;
            p.name = name;
            p.runs = true;
            all.push_back(p);
        }
    double last = -1;
    int skippedSince = 0;
    for (size_t i = 0; i < all.size(); ++i) {
        const auto at = std::find(order.begin(), order.end(), all[i].name);
        if (all[i].runs && at != order.end()) {
            last = double(at - order.begin());
            skippedSince = 0;
            keys.push_back({last, i});
        } else {
            keys.push_back({last + 0.5 + 1e-3 * ++skippedSince, i});
        }
    }
    std::stable_sort(keys.begin(), keys.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<ReportPass> out;
    for (const auto& k : keys) out.push_back(all[k.second]);
    return out;
}

GraphLayout layoutFrameGraph(const std::vector<ReportPass>& passes) {
    GraphLayout layout;
    for (size_t i = 0; i < passes.size(); ++i)
        layout.boxes.push_back({kArcArea, kTop + double(i) * kRowHeight, kBoxWidth, kBoxHeight});
    // An edge from the latest writer of each resource version to every reader.
    for (size_t to = 0; to < passes.size(); ++to) {
        if (!passes[to].runs) continue;
        std::map<size_t, std::vector<std::string>> byWriter;
        for (const auto& read : passes[to].reads)
            for (size_t from = to; from-- > 0;) {
                if (!passes[from].runs) continue;
                const auto& w = passes[from].writes;
                if (std::find(w.begin(), w.end(), read) != w.end()) {
                    byWriter[from].push_back(read);
                    break;
                }
            }
        for (auto& [from, resources] : byWriter) {
            GraphEdge e;
            e.from = from;
            e.to = to;
            e.resources = resources;
            e.reach = std::min(kArcArea - 12, 14.0 + 9.0 * double(to - from));
            layout.edges.push_back(e);
        }
    }
    layout.width = kArcArea + kBoxWidth + 760;
    layout.height = kTop * 2 + double(passes.size()) * kRowHeight;
    return layout;
}

std::string frameGraphSvg(const std::vector<ReportPass>& passes) {
    const GraphLayout l = layoutFrameGraph(passes);
    std::ostringstream s;
    s << "<svg xmlns=\"http://www.w3.org/2000/svg\" id=\"graph\" width=\"" << l.width << "\" height=\"" << l.height
      << "\" viewBox=\"0 0 " << l.width << " " << l.height << "\">\n"
      << "<defs><marker id=\"arrow\" markerWidth=\"8\" markerHeight=\"8\" refX=\"7\" refY=\"4\" orient=\"auto\">"
         "<path d=\"M0,0 L8,4 L0,8 z\" fill=\"#555\"/></marker></defs>\n";
    for (const GraphEdge& e : l.edges) {
        const GraphBox &a = l.boxes[e.from], &b = l.boxes[e.to];
        const double y0 = a.y + a.height * 0.5, y1 = b.y + b.height * 0.5, x = a.x;
        std::string names;
        for (const auto& r : e.resources) names += (names.empty() ? "" : ", ") + r;
        s << "<path d=\"M" << x << "," << y0 << " C" << x - e.reach << "," << y0 << " " << x - e.reach << "," << y1 << " "
          << x - 1 << "," << y1 << "\" fill=\"none\" stroke=\"#555\" stroke-width=\"1\" marker-end=\"url(#arrow)\"><title>"
          << htmlEscape(passes[e.from].name + " -> " + passes[e.to].name + ": " + names) << "</title></path>\n";
    }
    for (size_t i = 0; i < passes.size(); ++i) {
        const ReportPass& p = passes[i];
        const GraphBox& b = l.boxes[i];
        s << "<g data-check=\"pass:" << htmlEscape(p.name) << "\"><rect x=\"" << b.x << "\" y=\"" << b.y << "\" width=\""
          << b.width << "\" height=\"" << b.height << "\" rx=\"3\" fill=\"" << (p.runs ? kLiveBox : kSkippedBox) << "\"/>"
          << "<text x=\"" << b.x + 6 << "\" y=\"" << b.y + 15 << "\" font-size=\"12\" fill=\"" << (p.runs ? "#fff" : "#666")
          << "\">" << htmlEscape(p.name) << "</text></g>\n";
        // Beside the box: what it writes (and its kind), or why it does not run.
        std::string side;
        if (p.runs) {
            side = "[" + p.kind + "]";
            for (size_t w = 0; w < p.writes.size(); ++w) side += (w ? ", " : " \u2192 ") + p.writes[w];
        } else {
            side = p.reason;
        }
        s << "<text x=\"" << b.x + b.width + 8 << "\" y=\"" << b.y + 15 << "\" font-size=\"12\" fill=\""
          << (p.runs ? "#222" : "#888") << "\">" << htmlEscape(side.size() > 140 ? side.substr(0, 137) + "..." : side)
          << "<title>" << htmlEscape(side) << "</title></text>\n";
    }
    s << "</svg>\n";
    return s.str();
}

std::vector<TimingBar> layoutTimingBars(const std::vector<PassTiming>& timings, double width, double scaleMs) {
    double most = scaleMs;
    if (most <= 0)
        for (const auto& t : timings) most = std::max({most, t.medianMs, t.floorMs.value_or(0.0)});
    std::vector<TimingBar> bars;
    for (const auto& t : timings) {
        TimingBar b;
        b.timeWidth = most > 0 ? width * t.medianMs / most : 0.0;
        if (t.floorMs) b.floorWidth = most > 0 ? width * *t.floorMs / most : 0.0;
        bars.push_back(b);
    }
    return bars;
}

std::string timingBarsSvg(const std::vector<PassTiming>& timings, double scaleMs, const std::string& checkPrefix) {
    const std::vector<TimingBar> bars = layoutTimingBars(timings, kBarArea, scaleMs);
    // The label column fits the longest name (a bench variant's flags), at about 7 px a character.
    size_t longest = 0;
    for (const auto& t : timings) longest = std::max(longest, t.name.size());
    const double column = std::clamp(7.0 * double(longest) + 12.0, kBarLabel, 3 * kBarLabel);
    const double width = column + kBarArea + 260, height = 10 + kBarRow * double(timings.size());
    std::ostringstream s;
    s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" viewBox=\"0 0 " << width << " " << height << "\">\n";
    for (size_t i = 0; i < timings.size(); ++i) {
        const PassTiming& t = timings[i];
        const double y = 5 + kBarRow * double(i);
        s << "<text x=\"" << column - 6 << "\" y=\"" << y + 13 << "\" font-size=\"12\" text-anchor=\"end\">"
          << htmlEscape(t.name) << "</text>\n";
        s << "<rect data-check=\"bar:" << htmlEscape(checkPrefix + t.name) << "\" x=\"" << column << "\" y=\"" << y << "\" width=\""
          << bars[i].timeWidth << "\" height=\"12\" fill=\"" << kTimeBar << "\"><title>" << htmlEscape(t.name) << ": "
          << num(t.medianMs, 4) << " ms</title></rect>\n";
        std::string text = num(t.medianMs, 3) + " ms";
        if (bars[i].floorWidth) {
            s << "<rect data-check=\"floor:" << htmlEscape(checkPrefix + t.name) << "\" x=\"" << column << "\" y=\"" << y + 14
              << "\" width=\"" << *bars[i].floorWidth << "\" height=\"6\" fill=\"" << kFloorBar << "\"><title>floor "
              << num(*t.floorMs, 4) << " ms (" << htmlEscape(t.floorBasis) << ")</title></rect>\n";
            text += ", floor " + num(*t.floorMs, 3) + " ms" +
                     (*t.floorMs > 0 ? " (" + num(t.medianMs / *t.floorMs, 1) + "x)" : "");
        } else if (!t.noFloorReason.empty()) {
            text += ", no floor (" + t.noFloorReason + ")";
        }
        s << "<text x=\"" << column + std::max(bars[i].timeWidth, bars[i].floorWidth.value_or(0.0)) + 6 << "\" y=\""
          << y + 13 << "\" font-size=\"12\" fill=\"#444\">" << htmlEscape(text) << "</text>\n";
    }
    s << "</svg>\n";
    return s.str();
}

std::vector<ReportViewRule> reportViewRules(int shadowLight) {
    // One row per view of everyView() (a unit test holds the two lists together).
    const std::string shadowPass = "shadow_map_" + std::to_string(shadowLight);
    return {
        {DebugView::Final, "the displayed frame", ""},
        {DebugView::Depth, "gbuffer", ""},
        {DebugView::Normals, "gbuffer", ""},
        {DebugView::Diffuse, "gbuffer", ""},
        {DebugView::Position, "gbuffer", ""},
        {DebugView::Shininess, "gbuffer", ""},
        {DebugView::Specular, "gbuffer", ""},
        {DebugView::Texcoords, "gbuffer", ""},
        {DebugView::Lighting, "global_lights, local_lights (no albedo)", ""},
        {DebugView::Environment, "ibl_bake (environment cube)", "ibl"},
        {DebugView::Irradiance, "ibl_bake (irradiance)", "ibl"},
        {DebugView::Prefiltered, "ibl_bake (prefiltered specular)", "ibl"},
        {DebugView::Dfg, "ibl_bake (DFG LUT)", "ibl"},
        {DebugView::WorldPosition, "gbuffer", ""},
        {DebugView::EyeVector, "gbuffer", ""},
        {DebugView::DepthFitted, "gbuffer", ""},
        {DebugView::Tangent, "gbuffer", ""},
        {DebugView::InvalidPixels, "the HDR buffer (NaN/Inf)", ""},
        {DebugView::ExposureEv, "the HDR buffer (EV false colour)", ""},
        {DebugView::Velocity, "gbuffer (velocity)", ""},
        {DebugView::Ao, "ao_denoise", "ao_denoise"},
        {DebugView::BaseColor, "gbuffer (material inputs)", ""},
        {DebugView::Metallic, "gbuffer (material inputs)", ""},
        {DebugView::Roughness, "gbuffer (material inputs)", ""},
        {DebugView::Occlusion, "gbuffer (material inputs)", ""},
        {DebugView::Emissive, "emission (the emitted radiance alone)", ""},
        {DebugView::TermDiffuse, "global_lights, local_lights (the diffuse term alone)", ""},
        {DebugView::TermSpecular, "global_lights, local_lights (the specular term alone)", ""},
        {DebugView::TermClearcoat, "global_lights, ibl, local_lights (KHR_materials_clearcoat's layer alone)", ""},
        {DebugView::ShadowMap, shadowPass, shadowPass},
        {DebugView::LightRanges, "local_lights (light bounds)", "local_lights"},
        {DebugView::LightsPerTile, "local_lights (lights per tile)", "local_lights"},
        {DebugView::LightsPerCluster, "local_lights (lights per cluster)", "local_lights"},
    };
}

std::vector<ReportViewRule> reportViews(int shadowLight, const std::function<bool(const std::string&)>& runs) {
    const std::vector<ReportViewRule> rules = reportViewRules(shadowLight);
    std::vector<ReportViewRule> out;
    for (DebugView v : everyView())
        for (const auto& r : rules)
            if (r.view == v && (r.needs.empty() || runs(r.needs))) out.push_back(r);
    return out;
}

std::string frameReportHtml(const FrameReport& r) {
    std::ostringstream s;
    s << pageHead("lightpass report: " + r.source);
    s << "<h1>lightpass report: " << htmlEscape(r.source) << "</h1>\n<table class=\"meta\">\n"
      << "<tr><td>command</td><td><code id=\"command\">" << htmlEscape(r.commandLine) << "</code></td></tr>\n"
      << "<tr><td>device</td><td id=\"device\">" << htmlEscape(r.device)
      << (r.softwareRaster ? " (software rasteriser: GPU times are not meaningful)" : "") << "</td></tr>\n"
      << "<tr><td>scene</td><td id=\"scene\">" << htmlEscape(r.sceneCounts) << "</td></tr>\n"
      << "<tr><td>size</td><td>" << htmlEscape(r.size) << ", view " << htmlEscape(r.view) << "</td></tr>\n"
      << "<tr><td>frame</td><td>" << num(r.frameMs, 3) << " GPU ms (median of " << r.frames << " frames after " << r.warmup
      << " warm-up frames)</td></tr>\n"
      << "<tr><td>memory</td><td id=\"memory\">textures " << mib(r.poolBytes) << " pooled transients + "
      << mib(r.persistentBytes) << " persistent (environment, IBL, kept shadow atlases); the graph's live transients "
      << mib(r.graphTransientBytes) << " before pooling</td></tr>\n</table>\n";

    size_t running = 0;
    for (const auto& p : r.passes) running += p.runs ? 1 : 0;
    s << "<h2>Frame graph</h2>\n<p>" << running << " passes run, in execution order (blue); "
      << r.passes.size() - running
      << " candidates do not (grey, with the reason <code>graph --explain</code> gives). An arc joins a pass to a "
         "later one that reads what it wrote (hover it for the resources).</p>\n"
      << frameGraphSvg(r.passes);

    s << "<h2>GPU time per pass</h2>\n<p>Median GPU ms (timer queries) per pass, orange; its floor, teal: the bytes it "
         "must move at this GPU's "
      << htmlEscape(r.bandwidth) << ".</p>\n"
      << timingBarsSvg(r.timings);

    s << "<h2>Views</h2>\n<p>What <code>--view</code> offers and this frame has, each rendered with the same flags.</p>\n"
         "<div class=\"views\">\n";
    for (const ReportView& v : r.views) {
        s << "<figure><img data-check=\"view:" << htmlEscape(v.name) << "\" alt=\"" << htmlEscape(v.name) << "\" width=\""
          << v.image.width << "\" height=\"" << v.image.height << "\" src=\"" << pngDataUri(encodePng(v.image))
          << "\"><figcaption><b>" << htmlEscape(v.name) << "</b>: " << htmlEscape(v.shows) << "</figcaption></figure>\n";
    }
    s << "</div>\n";

    s << "<h2>Transient textures</h2>\n<table class=\"res\" id=\"transients\"><tr><th>resource</th><th>size</th>"
         "<th>format</th><th>MiB</th></tr>\n";
    for (const auto& t : r.transients)
        s << "<tr><td>" << htmlEscape(t.name) << "</td><td>" << t.width << "x" << t.height << "</td><td>"
          << htmlEscape(t.format) << "</td><td>" << num(double(t.bytes) / 1048576.0, 2) << "</td></tr>\n";
    s << "</table>\n" << pageTail();
    return s.str();
}

namespace {
// One CSV line's fields; a field may be quoted ("a,b"), with "" for a quote inside.
std::vector<std::string> csvFields(const std::string& line) {
    std::vector<std::string> fields(1);
    bool quoted = false;
    for (size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quoted) {
            if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') fields.back() += '"', ++i;
            else if (c == '"') quoted = false;
            else fields.back() += c;
        } else if (c == '"') {
            quoted = true;
        } else if (c == ',') {
            fields.emplace_back();
        } else if (c != '\r') {
            fields.back() += c;
        }
    }
    return fields;
}
}  // namespace

std::vector<SweepRow> parseSweepCsv(const std::string& text, const std::string& label) {
    std::istringstream in(text);
    std::string line;
    if (!std::getline(in, line)) throw Error(label + ": empty (not a lightpass sweep.csv)");
    const std::vector<std::string> header = csvFields(line);
    auto column = [&](const std::string& name, bool required) -> int {
        const auto at = std::find(header.begin(), header.end(), name);
        if (at == header.end()) {
            if (required) throw Error(label + ": line 1: no '" + name + "' column (not a lightpass sweep.csv)");
            return -1;
        }
        return int(at - header.begin());
    };
    const int knob = column("knob", true), value = column("value", true), reference = column("reference", true),
              frame = column("frame_ms", true), rmse = column("rmse", true), psnr = column("psnr_db", true),
              image = column("image", true), bake = column("ibl_bake_gpu_ms", false),
              source = column("reference_source", false), spp = column("reference_spp", false),
              noise = column("reference_noise_rmse", false), term = column("term", false),
              surfaceRel = column("surface_relative_error", false), termRel = column("term_relative_error", false);
    std::vector<SweepRow> rows;
    for (int lineNo = 2; std::getline(in, line); ++lineNo) {
        if (line.empty() || line == "\r") continue;
        const std::vector<std::string> f = csvFields(line);
        if (f.size() != header.size())
            throw Error(label + ": line " + std::to_string(lineNo) + ": " + std::to_string(f.size()) + " fields, the header has " +
                        std::to_string(header.size()));
        auto number = [&](int col) {
            try {
                size_t used = 0;
                const double v = std::stod(f[size_t(col)], &used);
                if (used != f[size_t(col)].size() || !std::isfinite(v)) throw std::invalid_argument("");
                return v;
            } catch (const std::exception&) {
                throw Error(label + ": line " + std::to_string(lineNo) + ": " + header[size_t(col)] + " " +
                            quoteUserText(f[size_t(col)]) + " is not a finite number");
            }
        };
        SweepRow r;
        r.knob = f[size_t(knob)];
        r.value = f[size_t(value)];
        r.image = f[size_t(image)];
        r.reference = f[size_t(reference)] == "1";
        r.frameMs = number(frame);
        r.rmse = number(rmse);
        r.psnrDb = number(psnr);
        if (bake >= 0) r.iblBakeMs = number(bake);
        if (source >= 0) r.referenceSource = f[size_t(source)];
        if (spp >= 0) r.referenceSpp = int(number(spp));
        if (noise >= 0) r.referenceNoiseRmse = number(noise);
        if (term >= 0 && surfaceRel >= 0 && termRel >= 0) {
            r.term = f[size_t(term)];
            r.surfaceRelativeError = number(surfaceRel);
            r.termRelativeError = number(termRel);
        }
        rows.push_back(r);
    }
    if (rows.empty()) throw Error(label + ": no rows (the sweep wrote no values)");
    return rows;
}

std::vector<size_t> paretoFront(const std::vector<std::pair<double, double>>& points) {
    std::vector<size_t> front;
    for (size_t i = 0; i < points.size(); ++i) {
        const auto [t, e] = points[i];
        bool dominated = false;
        for (size_t j = 0; j < points.size() && !dominated; ++j) {
            const auto [t2, e2] = points[j];
            dominated = j != i && t2 <= t && e2 <= e && (t2 < t || e2 < e);
        }
        if (!dominated) front.push_back(i);
    }
    return front;
}

bool sweepUsesBakeTime(const std::vector<SweepRow>& rows) {
    if (rows.empty()) return false;
    double fLo = rows[0].frameMs, fHi = fLo, bLo = rows[0].iblBakeMs, bHi = bLo;
    for (const auto& r : rows) {
        fLo = std::min(fLo, r.frameMs), fHi = std::max(fHi, r.frameMs);
        bLo = std::min(bLo, r.iblBakeMs), bHi = std::max(bHi, r.iblBakeMs);
    }
    return fHi <= 1.03 * fLo && bLo > 0.0 && bHi > 1.1 * bLo;
}

namespace {
double sweepTime(const SweepRow& r, bool bake) { return bake ? r.iblBakeMs : r.frameMs; }
double plotError(const SweepRow& r) { return std::max(r.rmse, 1e-7); }
}  // namespace

std::vector<PlotPoint> layoutSweepPlot(const std::vector<SweepRow>& rows, double width, double height) {
    const bool bake = sweepUsesBakeTime(rows);
    std::vector<std::pair<double, double>> pts;
    for (const auto& r : rows) pts.push_back({sweepTime(r, bake), plotError(r)});
    double tLo = pts[0].first, tHi = tLo, eLo = std::log10(pts[0].second), eHi = eLo;
    for (const auto& [t, e] : pts) {
        tLo = std::min(tLo, t), tHi = std::max(tHi, t);
        eLo = std::min(eLo, std::log10(e)), eHi = std::max(eHi, std::log10(e));
    }
    // A flat axis is drawn around its one value.
    if (tHi - tLo <= 0) tLo -= 0.5, tHi += 0.5;
    if (eHi - eLo <= 0) eLo -= 0.5, eHi += 0.5;
    const std::vector<size_t> front = paretoFront(pts);
    std::vector<PlotPoint> out;
    for (size_t i = 0; i < pts.size(); ++i) {
        PlotPoint p;
        // Inset so that no point sits on the frame; y grows down, so less error is lower.
        p.x = kPlotInset + (width - 2 * kPlotInset) * (pts[i].first - tLo) / (tHi - tLo);
        p.y = kPlotInset + (height - 2 * kPlotInset) * (1.0 - (std::log10(pts[i].second) - eLo) / (eHi - eLo));
        p.front = std::find(front.begin(), front.end(), i) != front.end();
        out.push_back(p);
    }
    return out;
}

std::string sweepReportHtml(const SweepReport& r) {
    std::ostringstream s;
    s << pageHead("lightpass sweep report: " + r.folder);
    s << "<h1>lightpass sweep report: " << htmlEscape(r.folder) << "</h1>\n<table class=\"meta\">\n"
      << "<tr><td>command</td><td><code id=\"command\">" << htmlEscape(r.commandLine) << "</code></td></tr>\n"
      << "</table>\n<p>Per knob: error against "
      << (std::any_of(r.rows.begin(), r.rows.end(), [](const SweepRow& row) { return row.referenceSource == "pathtraced"; })
              ? "the path tracer at the knob's best value's settings (its samples and noise under each plot)"
              : "the knob's best value")
      << " (RMSE of the linear HDR buffer, log scale) "
         "against GPU ms; the Pareto front (no other value both faster and better) in red. Each value's image "
         "below its plot, numbered as its point.</p>\n";
    std::vector<std::string> knobs;
    for (const auto& row : r.rows)
        if (std::find(knobs.begin(), knobs.end(), row.knob) == knobs.end()) knobs.push_back(row.knob);
    for (const std::string& knob : knobs) {
        std::vector<SweepRow> rows;
        std::vector<size_t> index;
        for (size_t i = 0; i < r.rows.size(); ++i)
            if (r.rows[i].knob == knob) rows.push_back(r.rows[i]), index.push_back(i);
        const bool bake = sweepUsesBakeTime(rows);
        const std::vector<PlotPoint> pts = layoutSweepPlot(rows, kPlotWidth, kPlotHeight);
        double tLo = sweepTime(rows[0], bake), tHi = tLo, eLo = plotError(rows[0]), eHi = eLo;
        for (const auto& row : rows) {
            tLo = std::min(tLo, sweepTime(row, bake)), tHi = std::max(tHi, sweepTime(row, bake));
            eLo = std::min(eLo, plotError(row)), eHi = std::max(eHi, plotError(row));
        }
        const double m = kPlotMargin, w = kPlotWidth + 2 * m, h = kPlotHeight + 2 * m;
        s << "<h2>" << htmlEscape(knob) << "</h2>\n<svg xmlns=\"http://www.w3.org/2000/svg\" data-check=\"plot:"
          << htmlEscape(knob) << "\" width=\"" << w << "\" height=\"" << h << "\" viewBox=\"0 0 " << w << " " << h << "\">\n"
          << "<rect x=\"" << m << "\" y=\"" << m << "\" width=\"" << kPlotWidth << "\" height=\"" << kPlotHeight
          << "\" fill=\"none\" stroke=\"#999\"/>\n"
          << "<text x=\"" << m + kPlotWidth / 2 << "\" y=\"" << h - 14 << "\" font-size=\"12\" text-anchor=\"middle\">"
          << (bake ? "IBL bake GPU ms (one-off, per environment change)" : "frame GPU ms (median)") << ": "
          << num(tLo, 3) << " .. " << num(tHi, 3) << "</text>\n"
          << "<text x=\"14\" y=\"" << m + kPlotHeight / 2 << "\" font-size=\"12\" text-anchor=\"middle\" transform=\"rotate(-90 14 "
          << m + kPlotHeight / 2 << ")\">RMSE (log): " << general(eLo) << " .. " << general(eHi) << "</text>\n";
        // The front, left to right.
        std::vector<size_t> front;
        for (size_t i = 0; i < pts.size(); ++i)
            if (pts[i].front) front.push_back(i);
        std::sort(front.begin(), front.end(), [&](size_t a, size_t b) { return pts[a].x < pts[b].x; });
        s << "<polyline fill=\"none\" stroke=\"" << kFrontPoint << "\" stroke-width=\"1.5\" points=\"";
        for (size_t i : front) s << m + pts[i].x << "," << m + pts[i].y << " ";
        s << "\"/>\n";
        for (size_t i = 0; i < pts.size(); ++i) {
            s << "<circle data-check=\"point:" << htmlEscape(knob) << ":" << i << "\" cx=\"" << m + pts[i].x << "\" cy=\""
              << m + pts[i].y << "\" r=\"5\" fill=\"" << (pts[i].front ? kFrontPoint : kOtherPoint) << "\"><title>"
              << htmlEscape(rows[i].value) << ": " << num(sweepTime(rows[i], bake), 4) << " ms, RMSE " << general(rows[i].rmse)
              << "</title></circle>\n<text x=\"" << m + pts[i].x + 7 << "\" y=\"" << m + pts[i].y - 6
              << "\" font-size=\"11\">" << i << ": " << htmlEscape(rows[i].value) << "</text>\n";
        }
        s << "</svg>\n";
        if (rows[0].referenceSource == "pathtraced")
            s << "<p class=\"reference\">Reference: the path tracer, " << rows[0].referenceSpp
              << " samples a pixel; its own noise adds about " << general(rows[0].referenceNoiseRmse) << " RMSE.</p>\n";
        if (!rows[0].term.empty())
            s << "<p class=\"term\">Relative luminance error over the surfaces: of the frame, and of "
              << (rows[0].term == "frame" ? std::string("the same (the knob changes every light)")
                                          : "the scene lit by its " + htmlEscape(rows[0].term) + " alone")
              << ".</p>\n";
        s << "<div class=\"views\">\n";
        for (size_t i = 0; i < rows.size(); ++i) {
            const SweepImage& img = r.images[index[i]];
            const int width = std::min(img.width, 320);
            const int height = std::max(1, int(std::lround(double(img.height) * width / std::max(img.width, 1))));
            s << "<figure style=\"width:" << std::max(width, 160) << "px\"><img data-check=\"image:" << htmlEscape(knob) << ":" << i << "\" alt=\""
              << htmlEscape(knob + " " + rows[i].value) << "\" width=\"" << width << "\" height=\"" << height << "\" src=\""
              << pngDataUri(img.png) << "\"><figcaption><b>" << i << ": " << htmlEscape(rows[i].value) << "</b>"
              << (rows[i].reference ? " (reference)" : "") << ", " << num(rows[i].frameMs, 3) << " ms"
              << (rows[i].iblBakeMs > 0 ? ", bake " + num(rows[i].iblBakeMs, 3) + " ms" : "") << ", RMSE " << general(rows[i].rmse)
              << (rows[i].term.empty() ? ""
                                       : ", surfaces " + general(100.0 * rows[i].surfaceRelativeError) + "%, " +
                                             htmlEscape(rows[i].term) + " " + general(100.0 * rows[i].termRelativeError) + "%")
              << (pts[i].front ? ", on the front" : "") << "</figcaption></figure>\n";
        }
        s << "</div>\n";
    }
    s << pageTail();
    return s.str();
}

BenchReport parseBenchJson(const std::string& text, const std::string& label) {
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
        throw Error(label + ": invalid JSON at byte " + std::to_string(e.byte));
    }
    const auto runs = j.find("runs");
    if (!j.is_object() || runs == j.end() || !runs->is_array() || runs->empty())
        throw Error(label + ": no \"runs\" (not a lightpass bench --timings-json file)");
    auto text_ = [](const nlohmann::json& o, const char* key) {
        const auto at = o.find(key);
        return at != o.end() && at->is_string() ? at->get<std::string>() : std::string();
    };
    auto number = [&](const nlohmann::json& o, const char* key, const std::string& where) {
        const auto at = o.find(key);
        if (at == o.end() || !at->is_number()) throw Error(label + ": " + where + ": no number \"" + key + "\"");
        return at->get<double>();
    };
    BenchReport r;
    r.file = label;
    r.device = text_(j, "device");
    r.scene = text_(j, "scene");
    r.commonFlags = text_(j, "common_flags");
    if (const auto bw = j.find("bandwidth"); bw != j.end() && bw->is_object())
        r.bandwidth = "compute copy " + num(number(*bw, "compute_GBps", "bandwidth"), 1) + " GB/s, fragment fill " +
                      num(number(*bw, "fragment_GBps", "bandwidth"), 1) + " GB/s";
    for (size_t i = 0; i < runs->size(); ++i) {
        const nlohmann::json& run = (*runs)[i];
        const std::string where = "runs[" + std::to_string(i) + "]";
        if (!run.is_object()) throw Error(label + ": " + where + ": not an object");
        BenchRun b;
        b.flags = text_(run, "flags");
        b.width = int(number(run, "width", where));
        b.height = int(number(run, "height", where));
        b.frames = int(number(run, "frames", where));
        if (run.contains("transient_texture_bytes")) b.transientBytes = size_t(number(run, "transient_texture_bytes", where));
        const auto passes = run.find("passes");
        if (passes == run.end() || !passes->is_object() || !passes->contains("frame"))
            throw Error(label + ": " + where + ": no \"passes\" with a \"frame\" time");
        for (const auto& [name, p] : passes->items()) {
            const double ms = number(p, "median_ms", where + ".passes." + name);
            if (name == "frame") {
                b.frameMs = ms;
                continue;
            }
            PassTiming t;
            t.name = name;
            t.medianMs = ms;
            if (p.contains("floor_ms")) {
                t.floorMs = number(p, "floor_ms", where + ".passes." + name);
                t.floorBasis = text_(p, "floor_basis");
            } else if (j.contains("bandwidth")) {
                t.noFloorReason = "moves no texture bytes";
            }
            b.passes.push_back(t);
        }
        std::stable_sort(b.passes.begin(), b.passes.end(),
                         [](const PassTiming& a, const PassTiming& c) { return a.medianMs > c.medianMs; });
        r.runs.push_back(std::move(b));
    }
    return r;
}

std::string benchReportHtml(const BenchReport& r) {
    std::ostringstream s;
    s << pageHead("lightpass bench report: " + r.scene);
    s << "<h1>lightpass bench report: " << htmlEscape(r.scene) << "</h1>\n<table class=\"meta\">\n"
      << "<tr><td>command</td><td><code id=\"command\">" << htmlEscape(r.commandLine) << "</code></td></tr>\n"
      << "<tr><td>file</td><td><code>" << htmlEscape(r.file) << "</code></td></tr>\n"
      << "<tr><td>device</td><td id=\"device\">" << htmlEscape(r.device) << "</td></tr>\n"
      << "<tr><td>flags of every variant</td><td><code>" << htmlEscape(r.commonFlags) << "</code></td></tr>\n"
      << "<tr><td>floors</td><td>"
      << (r.bandwidth.empty() ? std::string("not measured (bench without --floors)") : htmlEscape(r.bandwidth))
      << "</td></tr>\n</table>\n";
    // The frame per variant, then each variant's passes, all on one scale.
    std::vector<PassTiming> frames;
    double most = 0;
    for (const BenchRun& run : r.runs) {
        frames.push_back({run.flags.empty() ? "(no flags)" : run.flags, run.frameMs, std::nullopt, "", ""});
        for (const auto& p : run.passes) most = std::max({most, p.medianMs, p.floorMs.value_or(0.0)});
    }
    s << "<h2>Frame GPU ms per variant</h2>\n" << timingBarsSvg(frames, 0, "variant:");
    for (size_t i = 0; i < r.runs.size(); ++i) {
        const BenchRun& run = r.runs[i];
        s << "<h2>" << htmlEscape(run.flags.empty() ? "(no flags)" : run.flags) << "</h2>\n<p>" << run.width << "x"
          << run.height << ", median of " << run.frames << " frames: " << num(run.frameMs, 3) << " GPU ms; transient textures "
          << mib(run.transientBytes) << ". Passes by GPU time (orange), with floors (teal) where measured; one scale for "
          << "every variant.</p>\n"
          << timingBarsSvg(run.passes, most, std::to_string(i) + ":");
    }
    s << pageTail();
    return s.str();
}

}  // namespace lp::app
