#include "engine/io/obj_text.hpp"

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

// A token as it is quoted in a message: control bytes (a lone CR, ESC) written as \xNN, so that the
// message stays one clean line on a terminal, and long tokens cut.
std::string quoted(const std::string& token) {
    return "'" + printableBytes(token.substr(0, 64)) + (token.size() > 64 ? "...'" : "'");
}

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
        }
        out += line;
        out += '\n';
    }
    return out;
}

}  // namespace lp
