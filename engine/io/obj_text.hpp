#pragma once
// Checks of OBJ and MTL text that tinyobjloader does not make: it reads "nan", "a" or "7x" as 0 and an
// index too large for an int wraps around. These scans find such values first, so the loader can name
// the file and line.
#include <string>
#include <vector>

namespace lp {

// What scanObjText found besides errors: positions as written (tinyobjloader's are replaced by these,
// so NaN/Inf survive to be counted and dropped with their triangles; a coordinate beyond +-1e18 is
// stored as Inf), and counted oddities to warn about.
struct ObjTextScan {
    std::vector<float> positions;  // xyz per "v" line, in order
    size_t nonFinitePositions = 0;
    size_t firstNonFinitePositionLine = 0;
    size_t nonFiniteAttributes = 0;  // vn/vt components: ignored by the loader (normals are regenerated)
    size_t firstNonFiniteAttributeLine = 0;
};

// Throws lp::Error("<file>:<line>: <what>") for a number that does not parse, a "v" line with fewer than
// 3 coordinates and a face index that is not a whole number, is 0 or does not fit in an int.
ObjTextScan scanObjText(const std::string& text, const std::string& file);

// MTL text with every numeric statement checked: a value that does not parse or is not finite is
// replaced by the loader's default for that statement (or the line dropped where there is none), with
// one warning "<file>:<line>: ..." each, appended to `warnings`.
std::string sanitizeMtlText(const std::string& text, const std::string& file, std::vector<std::string>& warnings);

}  // namespace lp
