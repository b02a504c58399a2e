// FXAA 3.11 "quality" (Lottes 2011, the PC quality path, preset 39's edge search) on a
// tone-mapped, sRGB-encoded image. Shared by the FXAA pass and the shader tests.
//
// Positions are in pixels (pixel p's centre is p + 0.5) and every fetch is a bilinear computed by
// hand from texelFetch, clamped at the edges: the result does not depend on the texture's filter
// state or a driver's 8-bit filter weights. Luma is perceptual luma of the encoded values (Rec. 601
// weights), computed here from the colour.
//
// One deliberate difference from the reference: where the 3x3 neighbourhood is constant along the
// edge (a straight, pixel-aligned horizontal or vertical step) the sub-pixel term is not applied. Such
// an edge has no aliasing to remove, and FXAA 3.11's sub-pixel blend would blur it by about 5%.
#ifndef LP_FXAA_GLSL
#define LP_FXAA_GLSL

const float FXAA_SUBPIX = 0.75;            // amount of sub-pixel aliasing removal (Lottes' default)
const float FXAA_EDGE_THRESHOLD = 0.166;   // minimum local contrast, relative to the local maximum
const float FXAA_EDGE_THRESHOLD_MIN = 0.0833;  // darks below this are left alone
const int FXAA_SEARCH_STEPS = 12;          // preset 39: 12 steps along the edge
// Preset 39's step lengths in pixels (26.5 px each way at most).
const float FXAA_STEP[12] = float[12](1.0, 1.0, 1.0, 1.0, 1.0, 1.5, 2.0, 2.0, 2.0, 2.0, 4.0, 8.0);
// Along-edge luma differences below this count as constant (half an 8-bit step).
const float FXAA_STRAIGHT_EPS = 0.5 / 255.0;

float fxaaLuma(vec3 c) { return dot(c, vec3(0.299, 0.587, 0.114)); }

vec3 fxaaTexel(sampler2D src, ivec2 i) { return texelFetch(src, clamp(i, ivec2(0), textureSize(src, 0) - 1), 0).rgb; }

// Bilinear colour at pixel position pos (centres at i + 0.5), clamp to edge.
vec3 fxaaColorAt(sampler2D src, vec2 pos) {
    vec2 c = pos - 0.5;
    vec2 f0 = floor(c);
    vec2 f = c - f0;
    ivec2 i = ivec2(f0);
    vec3 a = mix(fxaaTexel(src, i), fxaaTexel(src, i + ivec2(1, 0)), f.x);
    vec3 b = mix(fxaaTexel(src, i + ivec2(0, 1)), fxaaTexel(src, i + ivec2(1, 1)), f.x);
    return mix(a, b, f.y);
}

float fxaaLumaAt(sampler2D src, vec2 pos) { return fxaaLuma(fxaaColorAt(src, pos)); }
float fxaaLumaOff(sampler2D src, ivec2 p, int dx, int dy) { return fxaaLuma(fxaaTexel(src, p + ivec2(dx, dy))); }

// The anti-aliased colour of pixel p. "N" is row y - 1, "S" row y + 1, "W" column x - 1.
vec3 fxaaQuality(sampler2D src, ivec2 p) {
    vec2 posM = vec2(p) + 0.5;
    vec3 rgbM = fxaaTexel(src, p);
    float lumaM = fxaaLuma(rgbM);
    float lumaS = fxaaLumaOff(src, p, 0, 1);
    float lumaE = fxaaLumaOff(src, p, 1, 0);
    float lumaN = fxaaLumaOff(src, p, 0, -1);
    float lumaW = fxaaLumaOff(src, p, -1, 0);
    float rangeMax = max(max(lumaN, lumaW), max(lumaE, max(lumaS, lumaM)));
    float rangeMin = min(min(lumaN, lumaW), min(lumaE, min(lumaS, lumaM)));
    float range = rangeMax - rangeMin;
    if (range < max(FXAA_EDGE_THRESHOLD_MIN, rangeMax * FXAA_EDGE_THRESHOLD)) return rgbM;  // no edge here

    float lumaNW = fxaaLumaOff(src, p, -1, -1);
    float lumaSE = fxaaLumaOff(src, p, 1, 1);
    float lumaNE = fxaaLumaOff(src, p, 1, -1);
    float lumaSW = fxaaLumaOff(src, p, -1, 1);
    // Edge direction: second differences across rows (horizontal edge) against across columns.
    float lumaNS = lumaN + lumaS, lumaWE = lumaW + lumaE;
    float edgeHorz = abs(-2.0 * lumaW + lumaNW + lumaSW) + 2.0 * abs(-2.0 * lumaM + lumaNS) + abs(-2.0 * lumaE + lumaNE + lumaSE);
    float edgeVert = abs(-2.0 * lumaN + lumaNW + lumaNE) + 2.0 * abs(-2.0 * lumaM + lumaWE) + abs(-2.0 * lumaS + lumaSW + lumaSE);
    bool horzSpan = edgeHorz >= edgeVert;
    // Sub-pixel term: how far the pixel is from its 3x3 low-pass, relative to the local range.
    float subpixA = 2.0 * (lumaNS + lumaWE) + (lumaNW + lumaSW + lumaNE + lumaSE);
    float subpixC = clamp(abs(subpixA / 12.0 - lumaM) / range, 0.0, 1.0);
    bool straight = horzSpan
        ? max(max(abs(lumaW - lumaM), abs(lumaE - lumaM)),
              max(max(abs(lumaNW - lumaN), abs(lumaNE - lumaN)), max(abs(lumaSW - lumaS), abs(lumaSE - lumaS)))) <= FXAA_STRAIGHT_EPS
        : max(max(abs(lumaN - lumaM), abs(lumaS - lumaM)),
              max(max(abs(lumaNW - lumaW), abs(lumaSW - lumaW)), max(abs(lumaNE - lumaE), abs(lumaSE - lumaE)))) <= FXAA_STRAIGHT_EPS;

    // The neighbour across the edge with the larger gradient: N/S for a horizontal edge, W/E otherwise.
    float luma1 = horzSpan ? lumaN : lumaW;
    float luma2 = horzSpan ? lumaS : lumaE;
    float gradient1 = luma1 - lumaM, gradient2 = luma2 - lumaM;
    bool pair1 = abs(gradient1) >= abs(gradient2);
    float gradientScaled = 0.25 * max(abs(gradient1), abs(gradient2));
    float lengthSign = pair1 ? -1.0 : 1.0;  // towards the chosen neighbour
    float lumaLocalAverage = 0.5 * (pair1 ? luma1 + lumaM : luma2 + lumaM);

    // Search along the edge, half a pixel towards the chosen neighbour, both ways until the luma
    // there leaves the edge's average by a quarter of the gradient.
    vec2 along = horzSpan ? vec2(1.0, 0.0) : vec2(0.0, 1.0);
    vec2 posB = posM + (horzSpan ? vec2(0.0, 0.5 * lengthSign) : vec2(0.5 * lengthSign, 0.0));
    vec2 posN = posB - along * FXAA_STEP[0];
    vec2 posP = posB + along * FXAA_STEP[0];
    float lumaEndN = fxaaLumaAt(src, posN) - lumaLocalAverage;
    float lumaEndP = fxaaLumaAt(src, posP) - lumaLocalAverage;
    bool doneN = abs(lumaEndN) >= gradientScaled;
    bool doneP = abs(lumaEndP) >= gradientScaled;
    for (int k = 1; k < FXAA_SEARCH_STEPS && !(doneN && doneP); ++k) {
        if (!doneN) {
            posN -= along * FXAA_STEP[k];
            lumaEndN = fxaaLumaAt(src, posN) - lumaLocalAverage;
            doneN = abs(lumaEndN) >= gradientScaled;
        }
        if (!doneP) {
            posP += along * FXAA_STEP[k];
            lumaEndP = fxaaLumaAt(src, posP) - lumaLocalAverage;
            doneP = abs(lumaEndP) >= gradientScaled;
        }
    }
    float dstN = horzSpan ? posM.x - posN.x : posM.y - posN.y;
    float dstP = horzSpan ? posP.x - posM.x : posP.y - posM.y;
    bool lumaMLTZero = lumaM - lumaLocalAverage < 0.0;
    // The nearer end decides: the edge is a good span there when its luma moves the other way from M.
    bool nearerN = dstN < dstP;
    bool goodSpan = nearerN ? ((lumaEndN < 0.0) != lumaMLTZero) : ((lumaEndP < 0.0) != lumaMLTZero);
    float pixelOffset = goodSpan ? 0.5 - min(dstN, dstP) / (dstN + dstP) : 0.0;
    float subpixF = (-2.0 * subpixC + 3.0) * subpixC * subpixC;
    float subpixH = straight ? 0.0 : subpixF * subpixF * FXAA_SUBPIX;
    float offset = max(pixelOffset, subpixH);
    vec2 pos = posM + (horzSpan ? vec2(0.0, offset * lengthSign) : vec2(offset * lengthSign, 0.0));
    return fxaaColorAt(src, pos);
}

#endif
