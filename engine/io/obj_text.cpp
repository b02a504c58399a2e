#include "engine/io/obj_text.hpp"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <sstream>

#include "engine/core/error.hpp"
#include "engine/scene/mesh.hpp"

namespace lp {
namespace {

std::vector<std::string> splitWords(const std::string& line) {
    std::vector<std::string> words;
    std::istringstream in(line);
    for (std::string w; in >> w;) words.push_back(w);
    return words;
}

// The whole token must be a number; NaN and Inf parse (the caller decides what they mean).
bool parseNumber(const std::string& token, double& out) {
    if (token.empty()) return false;
    errno = 0;
    char* end = nullptr;
    out = std::strtod(token.c_str(), &end);
    if (end != token.c_str() + token.size()) return false;
    if (errno == ERANGE && std::abs(out) > 1.0) out = std::copysign(HUGE_VAL, out);  // overflow: Inf
    return true;
}

bool finiteAsFloat(double v) { return std::isfinite(v) && std::abs(v) <= double(std::numeric_limits<float>::max()); }

// Past this a position's squared length overflows a float (bounds, camera framing, shadow fitting):
// such a vertex counts as Inf.
constexpr double kMaxPositionCoordinate = 1e18;

struct LineReader {
    const std::string& text;
    size_t pos = 0, number = 0;
    bool next(std::string& line) {
        if (pos >= text.size()) return false;
        size_t end = text.find('\n', pos);
        line = text.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
        pos = end == std::string::npos ? text.size() : end + 1;
        ++number;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        return true;
    }
};

// A token as it is quoted in a message (quoteUserText: control bytes such as a lone CR or an ESC
// written as \xNN, so that the message stays one clean line on a terminal, and long tokens cut).
std::string quoted(const std::string& token) { return quoteUserText(token); }

[[noreturn]] void failAt(const std::string& file, size_t line, const std::string& what) {
    throw Error(file + ":" + std::to_string(line) + ": " + what);
}

// One face/line/point corner "v", "v/t", "v//n" or "v/t/n": each present part a non-zero int.
void checkCorner(const std::string& corner, const std::string& file, size_t line) {
    size_t start = 0;
    for (int part = 0; part < 3 && start <= corner.size(); ++part) {
        size_t slash = corner.find('/', start);
        std::string index = corner.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
        if (!index.empty() || part == 0) {
            errno = 0;
            char* end = nullptr;
            const long long v = std::strtoll(index.c_str(), &end, 10);
            if (index.empty() || end != index.c_str() + index.size())
                failAt(file, line, quoted(corner) + " is not a vertex index");
            if (errno == ERANGE || v > INT_MAX || v < -INT_MAX)
                failAt(file, line, "index " + index + " is out of range");
            if (v == 0) failAt(file, line, "index 0 (OBJ indices start at 1)");
        }
        if (slash == std::string::npos) break;
        start = slash + 1;
    }
}

}  // namespace

ObjTextScan scanObjText(const std::string& text, const std::string& file) {
    ObjTextScan scan;
    constexpr uint64_t kMaxPolygonWork = uint64_t(1) << 25;  // one face of 5792 corners, or 32768 of 32
    uint64_t polygonWork = 0;
    LineReader reader{text};
    std::string line;
    while (reader.next(line)) {
        const size_t hash = line.find('#');
        if (hash != std::string::npos) line.resize(hash);
        const std::vector<std::string> w = splitWords(line);
        if (w.empty()) continue;
        const std::string& kind = w[0];
        if (kind == "v" || kind == "vn" || kind == "vt") {
            const size_t need = kind == "vt" ? 1 : 3;
            if (w.size() - 1 < need)
                failAt(file, reader.number, kind + " needs " + std::to_string(need) + " numbers, got " + std::to_string(w.size() - 1));
            bool finite = true;
            double xyz[3] = {0, 0, 0};
            for (size_t i = 1; i < w.size(); ++i) {
                double v = 0.0;
                if (!parseNumber(w[i], v)) failAt(file, reader.number, kind + ": " + quoted(w[i]) + " is not a number");
                if (!finiteAsFloat(v)) finite = false;
                if (i <= 3) xyz[i - 1] = v;
            }
            if (kind == "v") {
                for (double& c : xyz)
                    if (std::abs(c) > kMaxPositionCoordinate) {
                        c = std::copysign(HUGE_VAL, c);  // Inf: its triangles are dropped later
                        finite = false;
                    }
                for (double c : xyz) scan.positions.push_back(float(c));
                if (!finite && scan.nonFinitePositions++ == 0) scan.firstNonFinitePositionLine = reader.number;
            } else if (!finite && scan.nonFiniteAttributes++ == 0) {
                scan.firstNonFiniteAttributeLine = reader.number;
            }
        } else if (kind == "f" || kind == "l" || kind == "p") {
            for (size_t i = 1; i < w.size(); ++i) checkCorner(w[i], file, reader.number);
            // The parser's polygon triangulation takes time quadratic in a face's corners (one face of
            // 90000 corners ran for minutes): the squared corner counts of faces over 4 corners are
            // bounded in all.
            const uint64_t corners = w.size() - 1;
            if (kind == "f" && corners > 4) {
                polygonWork += corners * corners;
                if (polygonWork > kMaxPolygonWork)
                    failAt(file, reader.number,
                           "a face of " + std::to_string(corners) + " corners; polygons over 4 corners add up to more than " +
                               std::to_string(kMaxPolygonWork) + " squared corners (their triangulation takes quadratic time)");
            }
        }
    }
    return scan;
}

namespace {

// A colour or scalar statement the renderer reads, in its physical range: the statement rewritten
// when it changes (empty when it stands as written). A colour of one value is grey (the MTL
// specification's "g and b equal r"; tinyobjloader reads "Kd 0.5" as (0.5, 0, 0)); reflectances Kd
// and Ks outside [0, 1], a negative emission Ke, an exponent Ns outside [0, 10000] and a dissolve d or
// Tr outside [0, 1] are clamped with one warning "<file>:<line>: ..." (a reflectance above 1 would
// give back more light than arrives).
std::string rangedMtlStatement(const std::vector<std::string>& w, const std::string& file, size_t line,
                               std::vector<std::string>& warnings) {
    struct Range {
        const char* key;
        bool colour;
        double lo, hi;
    };
    static const Range kRanges[] = {{"Kd", true, 0.0, 1.0},  {"Ks", true, 0.0, 1.0}, {"Ke", true, 0.0, HUGE_VAL},
                                    {"Ka", true, -HUGE_VAL, HUGE_VAL}, {"Ns", false, 0.0, 10000.0}, {"d", false, 0.0, 1.0},
                                    {"Tr", false, 0.0, 1.0}};
    const Range* range = nullptr;
    for (const Range& r : kRanges) range = w[0] == r.key ? &r : range;
    if (!range || w.size() < 2) return {};
    std::vector<double> v;
    for (size_t i = 1; i < w.size() && i <= (range->colour ? 3u : 1u); ++i) {
        double x = 0.0;
        parseNumber(w[i], x);
        v.push_back(x);
    }
    const bool grey = range->colour && v.size() == 1;
    if (grey) v.assign(3, v[0]);
    bool clamped = false;
    for (double& x : v) {
        const double c = std::clamp(x, range->lo, range->hi);
        clamped = clamped || c != x;
        x = c;
    }
    if (!grey && !clamped) return {};
    std::ostringstream values;
    values.precision(9);
    for (size_t i = 0; i < v.size(); ++i) values << (i ? " " : "") << v[i];
    if (clamped) {
        std::string written = w[0];
        for (size_t i = 1; i < w.size(); ++i) written += " " + w[i].substr(0, 24);  // numbers: parsed above
        const std::string bounds = range->hi == HUGE_VAL ? "below 0"
                                                         : "outside [" + std::to_string(int(range->lo)) + ", " + std::to_string(int(range->hi)) + "]";
        warnings.push_back(file + ":" + std::to_string(line) + ": " + written + ": " + bounds + "; clamped to " + values.str());
    }
    return w[0] + " " + values.str();
}

}  // namespace

std::string sanitizeMtlText(const std::string& text, const std::string& file, std::vector<std::string>& warnings) {
    const Material defaults;
    auto triple = [](glm::vec3 c) {
        std::ostringstream s;
        s << c.x << " " << c.y << " " << c.z;
        return s.str();
    };
    // Statements the renderer reads get its defaults back; the others are dropped.
    const std::map<std::string, std::string> fallback = {{"Kd", triple(defaults.diffuse)},
                                                         {"Ks", triple(defaults.specular)},
                                                         {"Ke", triple(defaults.emission)},
                                                         {"Ns", std::to_string(defaults.shininess)}};
    static const char* const numeric[] = {"Ka", "Kd", "Ks", "Ke", "Kt", "Tf", "Ns", "Ni", "d", "Tr", "illum",
                                          "Pr", "Pm", "Ps", "Pc", "Pcr", "aniso", "anisor"};
    std::string out;
    out.reserve(text.size());
    LineReader reader{text};
    std::string line;
    while (reader.next(line)) {
        std::string code = line;
        const size_t hash = code.find('#');
        if (hash != std::string::npos) code.resize(hash);
        const std::vector<std::string> w = splitWords(code);
        bool isNumeric = false;
        for (const char* k : numeric) isNumeric = isNumeric || (!w.empty() && w[0] == k);
        if (isNumeric) {
            std::string bad;
            if (w.size() < 2) bad = "no value";
            for (size_t i = 1; i < w.size() && bad.empty(); ++i) {
                if (i == 1 && w[0] == "Tf" && (w[i] == "spectral" || w[i] == "xyz")) break;
                double v = 0.0;
                if (!parseNumber(w[i], v)) bad = quoted(w[i]) + " is not a number";
                else if (!finiteAsFloat(v)) bad = quoted(w[i]) + " is not a finite number";
            }
            if (!bad.empty()) {
                auto it = fallback.find(w[0]);
                warnings.push_back(file + ":" + std::to_string(reader.number) + ": " + w[0] + ": " + bad + "; " +
                                   (it != fallback.end() ? "using the default " + it->second : "line ignored"));
                if (it != fallback.end()) out += w[0] + " " + it->second + "\n";
                continue;
            }
            const std::string ranged = rangedMtlStatement(w, file, reader.number, warnings);
            if (!ranged.empty()) {
                out += ranged + "\n";
                continue;
            }
        }
        out += line;
        out += '\n';
    }
    return out;
}

}  // namespace lp
