// Importance sampling of the environment map for the path tracer: the tables of
// passes/path_trace_environment.hpp (buildEnvironmentDistribution), one float array: the marginal CDF
// over rows (H + 1), each row's conditional CDF (H x (W + 1)), each cell's density over the (u, v)
// square (W x H). Directions are in the map's frame (before the environment's rotation). Needs
// common/ibl.glsl (equirectUv, equirectDirection) and common/path_trace.glsl (the binding).
#ifndef LP_PATH_TRACE_ENVIRONMENT_GLSL
#define LP_PATH_TRACE_ENVIRONMENT_GLSL

layout(std430, binding = LP_PT_BIND_ENVIRONMENT) readonly buffer PtEnvironment { float uPtEnvironment[]; };
uniform ivec2 uEnvironmentCells;  // W, H; (0, 0): no tables (the BRDF alone samples the environment)

// The cell i of n with cdf[i] <= x < cdf[i + 1], cdf the n + 1 floats from `first` (upper bound, so a
// cell of zero width is never chosen).
int lpPtEnvironmentCell(int first, int n, float x) {
    int lo = 0, hi = n + 1;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (uPtEnvironment[first + mid] <= x) lo = mid + 1;
        else hi = mid;
    }
    return clamp(lo - 1, 0, n - 1);
}

float lpPtEnvironmentCellPdf(int column, int row) {
    int w = uEnvironmentCells.x, h = uEnvironmentCells.y;
    return uPtEnvironment[(h + 1) + h * (w + 1) + row * w + column];
}

// A direction (map frame) from two uniform numbers and its density per steradian (0: none).
vec3 lpPtSampleEnvironment(vec2 u, out float pdf) {
    int w = uEnvironmentCells.x, h = uEnvironmentCells.y;
    int row = lpPtEnvironmentCell(0, h, u.y);
    float r0 = uPtEnvironment[row], r1 = uPtEnvironment[row + 1];
    int first = (h + 1) + row * (w + 1);
    int column = lpPtEnvironmentCell(first, w, u.x);
    float c0 = uPtEnvironment[first + column], c1 = uPtEnvironment[first + column + 1];
    float fy = r1 > r0 ? clamp((u.y - r0) / (r1 - r0), 0.0, 1.0) : 0.5;
    float fx = c1 > c0 ? clamp((u.x - c0) / (c1 - c0), 0.0, 1.0) : 0.5;
    vec2 uv = vec2((float(column) + fx) / float(w), (float(row) + fy) / float(h));
    float sinTheta = sin(uv.y * LP_IBL_PI);
    pdf = sinTheta > 0.0 ? lpPtEnvironmentCellPdf(column, row) / (2.0 * LP_IBL_PI * LP_IBL_PI * sinTheta) : 0.0;
    return equirectDirection(uv);
}

// The density per steradian with which lpPtSampleEnvironment picks direction d (map frame).
float lpPtEnvironmentPdf(vec3 d) {
    vec2 uv = equirectUv(d);
    int column = clamp(int(uv.x * float(uEnvironmentCells.x)), 0, uEnvironmentCells.x - 1);
    int row = clamp(int(uv.y * float(uEnvironmentCells.y)), 0, uEnvironmentCells.y - 1);
    float sinTheta = sin(uv.y * LP_IBL_PI);
    return sinTheta > 0.0 ? lpPtEnvironmentCellPdf(column, row) / (2.0 * LP_IBL_PI * LP_IBL_PI * sinTheta) : 0.0;
}

#endif
