// The report page's pure parts (app/report_html.cpp): escaping, encodings, thumbnails, the graph
// drawing's order and layout, the time bars, which views a frame has, the sweep CSV and its Pareto
// front. The page in a browser: tests/cli/check_report.py.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "app/report_html.hpp"
#include "engine/core/error.hpp"

namespace lp::app {
namespace {

TEST(ReportHtml, EscapesEveryCharacterThatCouldOpenATagOrEndAnAttribute) {
    EXPECT_EQ(htmlEscape("a<b>&\"c\"'d'"), "a&lt;b&gt;&amp;&quot;c&quot;&#39;d&#39;");
    EXPECT_EQ(htmlEscape("plain scene.json"), "plain scene.json");
    EXPECT_EQ(htmlEscape("&amp;"), "&amp;amp;");  // escaped once more, never taken as an entity
}

TEST(ReportHtml, UserTextOnTheFramePageIsEscapedEverywhere) {
    const std::string evil = "<script>alert('x')</script>\"&";
    FrameReport r;
    r.source = evil;
    r.commandLine = commandLine({"report", "--scene", evil});
    r.device = evil;
    r.size = evil;
    r.view = evil;
    r.bandwidth = evil;
    ReportPass p;
    p.name = evil;
    p.reason = evil;
    r.passes = {p};
    ReportPass q;
    q.name = "gbuffer";
    q.runs = true;
    q.kind = "raster";
    q.writes = {evil};
    r.passes.push_back(q);
    r.timings = {{evil, 1.0, 0.5, evil}};
    r.transients = {{evil, evil, 4, 4, 64}};
    Image8 image;
    image.width = image.height = 1;
    image.rgba = {1, 2, 3, 255};
    r.views = {{evil, evil, image}};
    const std::string html = frameReportHtml(r);
    EXPECT_EQ(html.find("<script>alert"), std::string::npos);
    EXPECT_EQ(html.find("'x'"), std::string::npos);
    EXPECT_NE(html.find("&lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt;"), std::string::npos);
    // Only the page's own two scripts.
    size_t scripts = 0;
    for (size_t at = html.find("<script>"); at != std::string::npos; at = html.find("<script>", at + 1)) ++scripts;
    EXPECT_EQ(scripts, 2u);
}

TEST(ReportHtml, Base64MatchesRfc4648) {
    EXPECT_EQ(base64(""), "");
    EXPECT_EQ(base64("f"), "Zg==");
    EXPECT_EQ(base64("fo"), "Zm8=");
    EXPECT_EQ(base64("foo"), "Zm9v");
    EXPECT_EQ(base64("foob"), "Zm9vYg==");
    EXPECT_EQ(base64("foobar"), "Zm9vYmFy");
    EXPECT_EQ(base64(std::string("\xff\xfe\x00", 3)), "//4A");
    EXPECT_EQ(pngDataUri("foo"), "data:image/png;base64,Zm9v");
}

TEST(ReportHtml, CommandLineQuotesWhatAShellWouldSplit) {
    EXPECT_EQ(shellQuote("--size"), "--size");
    EXPECT_EQ(shellQuote("scenes/cornell.json"), "scenes/cornell.json");
    EXPECT_EQ(shellQuote("my scene.json"), "'my scene.json'");
    EXPECT_EQ(shellQuote("it's"), "'it'\\''s'");
    EXPECT_EQ(shellQuote(""), "''");
    EXPECT_EQ(shellQuote("$HOME"), "'$HOME'");
    EXPECT_EQ(commandLine({"report", "--scene", "a b"}), "lightpass report --scene 'a b'");
}

TEST(ReportHtml, ThumbnailsAreAreaAveragesWithTheAspectKept) {
    Image8 image;
    image.width = 4;
    image.height = 2;
    // Two 2x2 blocks: left texels 0 and 100 (mean 50), right 200 and 255 (mean 227.5 -> 228).
    const uint8_t values[2][4] = {{0, 100, 200, 255}, {100, 0, 255, 200}};
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x)
            for (int c = 0; c < 4; ++c) image.rgba.push_back(values[y][x]);
    const Image8 half = shrinkToWidth(image, 2);
    ASSERT_EQ(half.width, 2);
    ASSERT_EQ(half.height, 1);
    EXPECT_EQ(half.rgba[0], 50);
    EXPECT_EQ(half.rgba[4], 228);
    EXPECT_EQ(shrinkToWidth(image, 4).rgba, image.rgba);  // fits: unchanged
    Image8 wide;
    wide.width = 640;
    wide.height = 360;
    wide.rgba.assign(size_t(640) * 360 * 4, 7);
    const Image8 thumb = shrinkToWidth(wide, 320);
    EXPECT_EQ(thumb.width, 320);
    EXPECT_EQ(thumb.height, 180);
    EXPECT_TRUE(std::all_of(thumb.rgba.begin(), thumb.rgba.end(), [](uint8_t v) { return v == 7; }));
}

ReportPass pass(const std::string& name, bool runs, std::vector<std::string> reads = {}, std::vector<std::string> writes = {}) {
    ReportPass p;
    p.name = name;
    p.runs = runs;
    p.kind = runs ? "compute" : "";
    p.reason = runs ? "" : "skipped: because";
    p.reads = std::move(reads);
    p.writes = std::move(writes);
    return p;
}

std::vector<std::string> names(const std::vector<ReportPass>& passes) {
    std::vector<std::string> n;
    for (const auto& p : passes) n.push_back(p.name);
    return n;
}

TEST(ReportHtml, PassesThatRunAreDrawnInExecutionOrderAndSkippedOnesAfterTheirPredecessor) {
    const std::vector<ReportPass> candidates = {pass("first_skipped", false), pass("a", true), pass("x", false),
                                                pass("y", false), pass("b", true), pass("c", true)};
    // b runs before a (the order the graph found); x and y stay right after a, in their order.
    EXPECT_EQ(names(passesInDrawingOrder(candidates, {"b", "a", "c"})),
              (std::vector<std::string>{"first_skipped", "b", "a", "x", "y", "c"}));
    // A pass that runs without being a candidate still gets its box, at its place.
    EXPECT_EQ(names(passesInDrawingOrder({pass("a", true)}, {"a", "extra"})), (std::vector<std::string>{"a", "extra"}));
}

TEST(ReportHtml, GraphEdgesJoinTheLatestWriterOfAVersionToItsReaders) {
    const std::vector<ReportPass> passes = {
        pass("gbuffer", true, {}, {"gbuffer.depth", "gbuffer.normal"}),
        pass("skipped", false, {"gbuffer.depth"}, {}),
        pass("lights", true, {"gbuffer.depth", "gbuffer.normal"}, {"hdr"}),
        pass("sky", true, {"gbuffer.depth", "hdr"}, {"hdr@1"}),
        pass("tonemap", true, {"hdr@1"}, {"ldr"}),
    };
    const GraphLayout l = layoutFrameGraph(passes);
    ASSERT_EQ(l.boxes.size(), passes.size());
    for (size_t i = 1; i < l.boxes.size(); ++i) {
        EXPECT_GT(l.boxes[i].y, l.boxes[i - 1].y + l.boxes[i - 1].height) << "box " << i << " overlaps the one above";
        EXPECT_EQ(l.boxes[i].x, l.boxes[0].x);
    }
    std::set<std::tuple<size_t, size_t, std::string>> edges;
    for (const GraphEdge& e : l.edges) {
        std::string r;
        for (const auto& name : e.resources) r += name + ";";
        edges.insert({e.from, e.to, r});
        EXPECT_LT(e.from, e.to);
        EXPECT_GT(e.reach, 0.0);
        EXPECT_LT(e.reach, l.boxes[0].x) << "an arc leaves the drawing";
    }
    const std::set<std::tuple<size_t, size_t, std::string>> expected = {
        {0, 2, "gbuffer.depth;gbuffer.normal;"}, {0, 3, "gbuffer.depth;"}, {2, 3, "hdr;"}, {3, 4, "hdr@1;"}};
    EXPECT_EQ(edges, expected);  // nothing to or from the skipped pass
    // A longer span reaches further out, so nested arcs stay apart.
    double reach03 = 0, reach23 = 0;
    for (const GraphEdge& e : l.edges) {
        if (e.from == 0 && e.to == 3) reach03 = e.reach;
        if (e.from == 2 && e.to == 3) reach23 = e.reach;
    }
    EXPECT_GT(reach03, reach23);
    EXPECT_GE(l.height, l.boxes.back().y + l.boxes.back().height);
    // The drawing names every pass, greys the skipped one and gives its reason.
    const std::string svg = frameGraphSvg(passes);
    for (const auto& p : passes) EXPECT_NE(svg.find("data-check=\"pass:" + p.name + "\""), std::string::npos) << p.name;
    EXPECT_NE(svg.find("skipped: because"), std::string::npos);
}

TEST(ReportHtml, TimeBarsShareOneScale) {
    const std::vector<PassTiming> timings = {{"a", 2.0, 1.0, "compute copy"}, {"b", 4.0, std::nullopt, ""}, {"c", 1.0, 8.0, "fragment fill"}};
    const std::vector<TimingBar> bars = layoutTimingBars(timings, 400.0);
    ASSERT_EQ(bars.size(), 3u);
    EXPECT_DOUBLE_EQ(bars[0].timeWidth, 100.0);  // the largest value (c's floor, 8 ms) spans the width
    EXPECT_DOUBLE_EQ(*bars[0].floorWidth, 50.0);
    EXPECT_DOUBLE_EQ(bars[1].timeWidth, 200.0);
    EXPECT_FALSE(bars[1].floorWidth);
    EXPECT_DOUBLE_EQ(*bars[2].floorWidth, 400.0);
    EXPECT_DOUBLE_EQ(layoutTimingBars({{"z", 0.0, std::nullopt, ""}}, 400.0)[0].timeWidth, 0.0);  // no division by 0
}

TEST(ReportHtml, EveryViewHasExactlyOneRuleAndNeedsItsPass) {
    const std::vector<ReportViewRule> rules = reportViewRules(1);
    for (DebugView v : everyView())
        EXPECT_EQ(std::count_if(rules.begin(), rules.end(), [&](const ReportViewRule& r) { return r.view == v; }), 1)
            << viewName(v);
    EXPECT_EQ(rules.size(), everyView().size());
    auto viewNames = [](const std::vector<ReportViewRule>& rs) {
        std::set<std::string> n;
        for (const auto& r : rs) n.insert(viewName(r.view));
        return n;
    };
    const std::set<std::string> bare = viewNames(reportViews(1, [](const std::string&) { return false; }));
    EXPECT_TRUE(bare.count("final") && bare.count("depth") && bare.count("normals") && bare.count("velocity"));
    EXPECT_FALSE(bare.count("ao") || bare.count("shadowmap") || bare.count("environment") || bare.count("light-ranges"));
    const std::set<std::string> lit = viewNames(reportViews(1, [](const std::string& p) {
        return p == "ao_denoise" || p == "shadow_map_1" || p == "ibl" || p == "local_lights";
    }));
    EXPECT_TRUE(lit.count("ao") && lit.count("shadowmap") && lit.count("environment") && lit.count("dfg") &&
                lit.count("lights-per-tile"));
    // shadowmap shows --shadow-light's map, not another light's.
    EXPECT_FALSE(viewNames(reportViews(1, [](const std::string& p) { return p == "shadow_map_0"; })).count("shadowmap"));
}

const char* kSweepCsv =
    "knob,value,index,reference,frame_ms,gbuffer_ms,ibl_bake_gpu_ms,rmse,psnr_db,max_abs,non_finite,image\n"
    "shadow-size,512,0,0,1.5,0.5,0,0.02,30,0.1,0,shadow-size/0.png\n"
    "shadow-size,\"1,024\",1,0,2.5,0.5,0,0.01,40,0.1,0,shadow-size/1.png\n"
    "shadow-size,2048,2,1,4,0.5,0,0,999,0,0,shadow-size/2.png\n";

TEST(ReportHtml, SweepCsvIsReadWithQuotedFields) {
    const std::vector<SweepRow> rows = parseSweepCsv(kSweepCsv, "s/sweep.csv");
    ASSERT_EQ(rows.size(), 3u);
    EXPECT_EQ(rows[1].value, "1,024");
    EXPECT_DOUBLE_EQ(rows[1].frameMs, 2.5);
    EXPECT_DOUBLE_EQ(rows[0].rmse, 0.02);
    EXPECT_TRUE(rows[2].reference);
    EXPECT_FALSE(rows[0].reference);
    EXPECT_EQ(rows[2].image, "shadow-size/2.png");
}

TEST(ReportHtml, SweepAgainstThePathTracerNamesItsSamplesAndNoise) {
    const std::string csv =
        "knob,value,index,reference,frame_ms,rmse,psnr_db,max_abs,non_finite,image,reference_source,reference_spp,"
        "reference_noise_rmse\n"
        "shadow-pcf,off,0,0,1.5,0.03,30,0.1,0,shadow-pcf/0.png,pathtraced,256,0.0042\n"
        "shadow-pcf,poisson,1,0,2.5,0.02,34,0.1,0,shadow-pcf/1.png,pathtraced,256,0.0042\n";
    SweepReport report;
    report.folder = "s";
    report.rows = parseSweepCsv(csv, "s/sweep.csv");
    ASSERT_EQ(report.rows.size(), 2u);
    EXPECT_EQ(report.rows[0].referenceSource, "pathtraced");
    EXPECT_EQ(report.rows[1].referenceSpp, 256);
    EXPECT_DOUBLE_EQ(report.rows[1].referenceNoiseRmse, 0.0042);
    EXPECT_FALSE(report.rows[1].reference);
    // Without the columns (an older sweep.csv): against the best value.
    EXPECT_EQ(parseSweepCsv(kSweepCsv, "s/sweep.csv")[0].referenceSource, "best");
    report.images.assign(2, SweepImage{});
    const std::string page = sweepReportHtml(report);
    EXPECT_NE(page.find("error against the path tracer"), std::string::npos);
    EXPECT_NE(page.find("Reference: the path tracer, 256 samples a pixel; its own noise adds about 0.0042 RMSE."),
              std::string::npos);
}

TEST(ReportHtml, SweepShowsTheErrorOverSurfacesAndOfTheKnobsLightTerm) {
    const std::string csv =
        "knob,value,index,reference,frame_ms,rmse,psnr_db,max_abs,non_finite,image,reference_source,reference_spp,"
        "reference_noise_rmse,surface_pixels,surface_rmse,surface_relative_error,term,term_rmse,term_relative_error\n"
        "shadow-pcf,off,0,0,1.5,0.03,30,0.1,0,shadow-pcf/0.png,pathtraced,256,0.0042,900,0.2,0.47,suns,0.03,0.0301\n"
        "shadow-pcf,poisson,1,0,2.5,0.02,34,0.1,0,shadow-pcf/1.png,pathtraced,256,0.0042,900,0.2,0.46,suns,0.03,0.0299\n";
    SweepReport report;
    report.folder = "s";
    report.rows = parseSweepCsv(csv, "s/sweep.csv");
    ASSERT_EQ(report.rows.size(), 2u);
    EXPECT_EQ(report.rows[0].term, "suns");
    EXPECT_DOUBLE_EQ(report.rows[1].surfaceRelativeError, 0.46);
    EXPECT_DOUBLE_EQ(report.rows[1].termRelativeError, 0.0299);
    EXPECT_TRUE(parseSweepCsv(kSweepCsv, "s/sweep.csv")[0].term.empty());  // an older sweep.csv
    report.images.assign(2, SweepImage{});
    const std::string page = sweepReportHtml(report);
    EXPECT_NE(page.find("the scene lit by its suns alone"), std::string::npos);
    EXPECT_NE(page.find("surfaces 46%, suns 2.99%"), std::string::npos) << page;
}

std::string errorOf(const std::string& csv) {
    try {
        parseSweepCsv(csv, "s/sweep.csv");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(ReportHtml, BadSweepCsvIsOneLineNamingFileLineAndField) {
    EXPECT_EQ(errorOf(""), "s/sweep.csv: empty (not a lightpass sweep.csv)");
    EXPECT_EQ(errorOf("knob,value\n"), "s/sweep.csv: line 1: no 'reference' column (not a lightpass sweep.csv)");
    const std::string header = "knob,value,index,reference,frame_ms,rmse,psnr_db,image\n";
    EXPECT_EQ(errorOf(header), "s/sweep.csv: no rows (the sweep wrote no values)");
    EXPECT_EQ(errorOf(header + "k,1,0,0,1.0,0.1,30,k/0.png\nk,2,1,1,abc,0,999,k/1.png\n"),
              "s/sweep.csv: line 3: frame_ms 'abc' is not a finite number");
    EXPECT_EQ(errorOf(header + "k,1,0,0,1.0\n"), "s/sweep.csv: line 2: 5 fields, the header has 8");
}

TEST(ReportHtml, ParetoFrontKeepsWhatNothingDominates) {
    const std::vector<std::pair<double, double>> pts = {{1, 3}, {2, 2}, {3, 1}, {3, 3}, {2, 2}, {4, 1}};
    // (3,3) is dominated by (2,2); (4,1) by (3,1); the two equal (2,2) do not dominate each other.
    EXPECT_EQ(paretoFront(pts), (std::vector<size_t>{0, 1, 2, 4}));
}

TEST(ReportHtml, SweepPlotPutsFasterLeftAndLessErrorLower) {
    const std::vector<SweepRow> rows = parseSweepCsv(kSweepCsv, "s/sweep.csv");
    const std::vector<PlotPoint> pts = layoutSweepPlot(rows, 500, 300);
    ASSERT_EQ(pts.size(), 3u);
    EXPECT_LT(pts[0].x, pts[1].x);
    EXPECT_LT(pts[1].x, pts[2].x);
    EXPECT_LT(pts[0].y, pts[1].y);  // more error: higher on the page (smaller y)
    EXPECT_LT(pts[1].y, pts[2].y);
    for (const auto& p : pts) {
        EXPECT_TRUE(p.front);
        EXPECT_GT(p.x, 0.0);
        EXPECT_LT(p.x, 500.0);
        EXPECT_GT(p.y, 0.0);
        EXPECT_LT(p.y, 300.0);
    }
    // The IBL knobs: frame time flat, the bake's varies: the plot's time is the bake's.
    std::vector<SweepRow> ibl = rows;
    for (size_t i = 0; i < ibl.size(); ++i) ibl[i].frameMs = 10.0, ibl[i].iblBakeMs = 1.0 + double(i);
    EXPECT_TRUE(sweepUsesBakeTime(ibl));
    EXPECT_FALSE(sweepUsesBakeTime(rows));
}

TEST(ReportHtml, SweepPageHasAPointAndAnImagePerValue) {
    SweepReport r;
    r.folder = "out<dir>";
    r.commandLine = "lightpass report --sweep 'out<dir>'";
    r.rows = parseSweepCsv(kSweepCsv, "s/sweep.csv");
    r.images.assign(3, SweepImage{"png", 96, 54});
    const std::string html = sweepReportHtml(r);
    for (int i = 0; i < 3; ++i) {
        EXPECT_NE(html.find("data-check=\"point:shadow-size:" + std::to_string(i) + "\""), std::string::npos);
        EXPECT_NE(html.find("data-check=\"image:shadow-size:" + std::to_string(i) + "\""), std::string::npos);
    }
    EXPECT_EQ(html.find("out<dir>"), std::string::npos);
    EXPECT_NE(html.find("1,024"), std::string::npos);
}

const char* kBenchJson = R"({"device": "GPU <x>", "scene": "s.json", "common_flags": "--size 64x36",
  "bandwidth": {"compute_GBps": 1000.0, "fragment_GBps": 2000.0},
  "runs": [
    {"flags": "--aa off", "width": 64, "height": 36, "frames": 2, "transient_texture_bytes": 1048576,
     "passes": {"frame": {"median_ms": 3.0}, "a": {"median_ms": 1.0, "floor_ms": 0.5, "floor_basis": "compute copy"},
                "b": {"median_ms": 2.0}}},
    {"flags": "--aa fxaa", "width": 64, "height": 36, "frames": 2,
     "passes": {"frame": {"median_ms": 4.0}, "a": {"median_ms": 0.5}}}]})";

TEST(ReportHtml, BenchJsonGivesEachVariantItsPassesByTime) {
    const BenchReport r = parseBenchJson(kBenchJson, "b.json");
    EXPECT_EQ(r.device, "GPU <x>");
    EXPECT_EQ(r.commonFlags, "--size 64x36");
    EXPECT_NE(r.bandwidth.find("compute copy 1000.0 GB/s"), std::string::npos);
    ASSERT_EQ(r.runs.size(), 2u);
    EXPECT_EQ(r.runs[0].flags, "--aa off");
    EXPECT_DOUBLE_EQ(r.runs[0].frameMs, 3.0);
    EXPECT_EQ(r.runs[0].transientBytes, 1048576u);
    ASSERT_EQ(r.runs[0].passes.size(), 2u);  // the frame is not a pass
    EXPECT_EQ(r.runs[0].passes[0].name, "b");  // most time first
    EXPECT_FALSE(r.runs[0].passes[0].floorMs);
    EXPECT_EQ(r.runs[0].passes[0].noFloorReason, "moves no texture bytes");  // floors measured, none for it
    EXPECT_DOUBLE_EQ(*r.runs[0].passes[1].floorMs, 0.5);
    const std::string html = benchReportHtml(r);
    EXPECT_EQ(html.find("GPU <x>"), std::string::npos);
    for (const char* id : {"bar:variant:--aa off", "bar:variant:--aa fxaa", "bar:0:a", "floor:0:a", "bar:0:b", "bar:1:a"})
        EXPECT_NE(html.find(std::string("data-check=\"") + id + "\""), std::string::npos) << id;
}

std::string benchErrorOf(const std::string& json) {
    try {
        parseBenchJson(json, "b.json");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(ReportHtml, BadBenchJsonIsOneLineNamingTheFileAndPlace) {
    EXPECT_EQ(benchErrorOf("{\"runs\": [1,"), "b.json: invalid JSON at byte 13");  // 12 bytes: it ends too early
    EXPECT_EQ(benchErrorOf("{\"runs\": x}"), "b.json: invalid JSON at byte 10");   // nlohmann counts from 1
    EXPECT_EQ(benchErrorOf("{}"), "b.json: no \"runs\" (not a lightpass bench --timings-json file)");
    EXPECT_EQ(benchErrorOf(R"({"runs": [{"width": 1, "height": 1, "frames": 1, "passes": {}}]})"),
              "b.json: runs[0]: no \"passes\" with a \"frame\" time");
    EXPECT_EQ(benchErrorOf(R"({"runs": [{"width": 1, "height": 1, "frames": 1, "passes": {"frame": {"median_ms": "x"}}}]})"),
              "b.json: runs[0].passes.frame: no number \"median_ms\"");
    EXPECT_EQ(benchErrorOf(R"({"runs": [{"height": 1}]})"), "b.json: runs[0]: no number \"width\"");
}

}  // namespace
}  // namespace lp::app
