#include "engine/render/shadows.hpp"

#include "engine/render/scene_gpu.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/core/error.hpp"

namespace lp {

std::vector<int> shadowCastingLights(const FrameData& frame) {
    std::vector<int> lights;
    if (!frame.scene || !frame.settings || !frame.settings->shadows.enabled) return lights;
    const auto& all = frameDirectionalLights(frame);
    for (int i = 0; i < int(all.size()) && int(lights.size()) < kMaxShadowedLights; ++i)
        if (all[size_t(i)].castsShadows || frame.settings->allPasses) lights.push_back(i);
    return lights;
}

std::vector<double> practicalSplits(double nearDist, double farDist, int cascades, double lambda) {
    std::vector<double> splits(size_t(cascades) + 1);
    for (int i = 0; i <= cascades; ++i) {
        const double t = double(i) / cascades;
        const double logSplit = nearDist * std::pow(farDist / nearDist, t);
        const double linSplit = nearDist + (farDist - nearDist) * t;
        splits[size_t(i)] = lambda * logSplit + (1.0 - lambda) * linSplit;
    }
    splits.front() = nearDist;  // exact ends, whatever pow rounds to
    splits.back() = farDist;
    return splits;
}

glm::ivec2 shadowAtlasGrid(int cascades) { return {cascades > 1 ? 2 : 1, cascades > 2 ? 2 : 1}; }

int originStepTexels(const ShadowSettings& settings) {
    return std::max(1, int(std::floor(double(settings.originStep) * settings.size)));
}

namespace {

void checkSettings(const ShadowSettings& s) {
    if (s.size < 16 || s.size > 8192) throw Error("shadows: size " + std::to_string(s.size) + " is outside [16, 8192]");
    if (s.cascades < 1 || s.cascades > kMaxShadowCascades)
        throw Error("shadows: cascades " + std::to_string(s.cascades) + " is outside [1, " + std::to_string(kMaxShadowCascades) + "]");
    if (!(s.splitLambda >= 0.0f && s.splitLambda <= 1.0f))
        throw Error("shadows: split lambda " + std::to_string(s.splitLambda) + " is outside [0, 1]");
    for (float b : {s.depthBias, s.slopeBias, s.normalBias})
        if (!std::isfinite(b) || b < 0.0f) throw Error("shadows: biases must be finite and >= 0");
    if (!(s.originStep >= 0.0f && s.originStep <= kMaxShadowOriginStep))
        throw Error("shadows: origin step " + std::to_string(s.originStep) + " is outside [0, " +
                    std::to_string(kMaxShadowOriginStep) + "]");
}

glm::dvec3 clampCoordinate(glm::dvec3 p) {
    for (int i = 0; i < 3; ++i)
        p[i] = std::isfinite(p[i]) ? std::clamp(p[i], -kMaxShadowCoordinate, kMaxShadowCoordinate) : 0.0;
    return p;
}

// Sutherland-Hodgman: the part of convex polygon `poly` where dot(plane.xyz, p) + plane.w >= 0.
std::vector<glm::dvec3> clipPolygon(const std::vector<glm::dvec3>& poly, glm::dvec4 plane) {
    std::vector<glm::dvec3> out;
    for (size_t i = 0; i < poly.size(); ++i) {
        const glm::dvec3 &a = poly[i], &b = poly[(i + 1) % poly.size()];
        const double da = glm::dot(glm::dvec3(plane), a) + plane.w, db = glm::dot(glm::dvec3(plane), b) + plane.w;
        if (da >= 0.0) out.push_back(a);
        if ((da >= 0.0) != (db >= 0.0)) out.push_back(a + (b - a) * (da / (da - db)));
    }
    return out;
}

glm::mat4 toFloat(const glm::dmat4& m) {
    glm::mat4 f(m);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(f[c][r])) throw Error("shadows: light matrix is not finite (scene bounds too large)");
    return f;
}

}  // namespace

std::optional<glm::dvec2> visibleDepthRange(glm::dvec3 lo, glm::dvec3 hi, const glm::dmat4& view, double nearPlane,
                                            double farPlane, double tanX, double tanY) {
    // Eye space looks down -z; the frustum is d = -z in [near, far], |x| <= d tanX, |y| <= d tanY.
    const glm::dvec4 planes[6] = {{0, 0, -1, -nearPlane}, {0, 0, 1, farPlane}, {-1, 0, -tanX, 0},
                                  {1, 0, -tanX, 0},        {0, -1, -tanY, 0},  {0, 1, -tanY, 0}};
    auto corner = [&](int c) {
        return glm::dvec3(view * glm::dvec4((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z, 1.0));
    };
    static const int faces[6][4] = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};
    double dMin = std::numeric_limits<double>::max(), dMax = std::numeric_limits<double>::lowest();
    for (const auto& face : faces) {
        std::vector<glm::dvec3> poly{corner(face[0]), corner(face[1]), corner(face[2]), corner(face[3])};
        for (const glm::dvec4& plane : planes)
            if (!poly.empty()) poly = clipPolygon(poly, plane);
        for (const glm::dvec3& p : poly) dMin = std::min(dMin, -p.z), dMax = std::max(dMax, -p.z);
    }
    // The camera inside the box: the near plane's own window is inside the bounds too.
    const glm::dvec3 eye(glm::inverse(view)[3]);
    if (glm::all(glm::greaterThanEqual(eye, lo)) && glm::all(glm::lessThanEqual(eye, hi))) dMin = nearPlane;
    if (!(dMin <= dMax)) return std::nullopt;
    return glm::dvec2(std::max(dMin, nearPlane), std::min(dMax, farPlane));
}

ShadowFrustum fitShadowFrustum(const FrameData& frame, glm::vec3 lightDirection, const ShadowFrustum* previous) {
    const ShadowSettings& settings = frame.settings->shadows;
    checkSettings(settings);
    glm::dvec3 f(lightDirection);
    const double len = glm::length(f);
    if (!std::isfinite(len) || len < 1e-20) throw Error("shadows: a directional light has a zero or non-finite direction");
    f /= len;

    ShadowFrustum out;
    out.lightDirection = f;
    out.tileSize = settings.size;
    const glm::ivec2 grid = shadowAtlasGrid(settings.cascades);
    out.columns = grid.x;
    out.rows = grid.y;

    // Light view: looks along f (-z), an orthonormal basis without translation (translation goes
    // into the projection, so huge coordinates never meet a lookAt's eye position).
    const glm::dvec3 up = std::abs(f.y) < 0.99 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
    const glm::dvec3 lx = glm::normalize(glm::cross(f, up));
    const glm::dvec3 ly = glm::cross(lx, f);
    glm::dmat4 lightView(1.0);
    for (int i = 0; i < 3; ++i) {
        lightView[i][0] = lx[i];
        lightView[i][1] = ly[i];
        lightView[i][2] = -f[i];
    }

    // Scene bounds in the frame's pose (an animated model's bounds follow it), clamped; an empty
    // scene is a unit box at the origin. Without the GPU scene (a graph only described) the rest pose's.
    glm::vec3 flo, fhi;
    if (frame.gpu) frame.gpu->bounds(*frame.scene, flo, fhi);
    else frame.scene->bounds(flo, fhi);
    glm::dvec3 lo = clampCoordinate(glm::dvec3(flo)), hi = clampCoordinate(glm::dvec3(fhi));
    if (!(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z)) lo = glm::dvec3(-0.5), hi = glm::dvec3(0.5);
    const double magnitude = std::max({1.0, glm::length(lo), glm::length(hi)});
    const double tiny = 1e-6 * magnitude;  // below this, extents are rounding noise

    const glm::dmat4 view(frame.view);
    const glm::dmat4 eyeToWorld = glm::inverse(view);
    out.eyeToLight = glm::mat3(glm::dmat3(lightView) * glm::dmat3(eyeToWorld));
    glm::dvec3 lsLo(std::numeric_limits<double>::max()), lsHi(std::numeric_limits<double>::lowest());
    for (int c = 0; c < 8; ++c) {
        glm::dvec4 p((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z, 1.0);
        glm::dvec3 ls(lightView * p);
        lsLo = glm::min(lsLo, ls);
        lsHi = glm::max(lsHi, ls);
    }

    // Symmetric perspective: tangents of the half angles from the projection.
    const double tanY = 1.0 / double(frame.projection[1][1]), tanX = 1.0 / double(frame.projection[0][0]);
    const double k2 = tanX * tanX + tanY * tanY;

    // The camera depth range worth covering: [near, far] clipped to the scene's depth range. For
    // stable texels the clip uses the scene's bounding sphere (turning the camera changes nothing)
    // and snaps to a 2^(1/4) grid (moving changes the splits only when it crosses a grid step).
    const double nearPlane = std::max(double(frame.nearPlane), 1e-6);
    const double farPlane = std::max(double(frame.farPlane), nearPlane * (1.0 + 1e-6));
    const glm::dvec3 sceneCentre = 0.5 * (lo + hi);
    const double sceneRadius = 0.5 * glm::length(hi - lo);
    const double centreDistance = glm::length(glm::dvec3(eyeToWorld[3]) - sceneCentre);
    auto snapDown = [](double z) { return std::exp2(std::floor(std::log2(z) * 4.0) / 4.0); };
    auto snapUp = [](double z) { return std::exp2(std::ceil(std::log2(z) * 4.0) / 4.0); };
    double zNear = nearPlane, zFar = farPlane;
    if (centreDistance - sceneRadius > nearPlane) zNear = std::max(nearPlane, snapDown(centreDistance - sceneRadius));
    if (centreDistance + sceneRadius < farPlane) zFar = std::min(farPlane, snapUp(centreDistance + sceneRadius));
    // The depths where the scene is actually visible: its bounds clipped by the view frustum. A
    // cascade whose slice lies wholly outside them serves no pixel and is dropped (its neighbours
    // take its depths); the slices themselves stay on the stable range above.
    const std::optional<glm::dvec2> visible = visibleDepthRange(lo, hi, view, nearPlane, farPlane, tanX, tanY);
    if (!(zFar > zNear * (1.0 + 1e-6)) || !visible) zNear = nearPlane, zFar = farPlane;  // scene out of view: any splits do
    const std::vector<double> splits = practicalSplits(zNear, zFar, settings.cascades, settings.splitLambda);
    out.visibleNear = visible ? visible->x : zNear;
    out.visibleFar = visible ? visible->y : zFar;
    auto rangeText = [](double a, double b) {
        char t[64];
        std::snprintf(t, sizeof t, "%.3g..%.3g m", a, b);
        return std::string(t);
    };
    const glm::dvec3 camPos(eyeToWorld[3]);
    const glm::dvec3 camForward = -glm::normalize(glm::dvec3(eyeToWorld[2]));

    // Depth: the whole scene along the light, padded so its faces never clip.
    const double depthPad = std::max(1e-3 * (lsHi.z - lsLo.z), tiny);
    const double nearZ = -lsHi.z - depthPad, farZ = -lsLo.z + depthPad;  // distances along f
    const double sceneSide = std::max(lsHi.x - lsLo.x, lsHi.y - lsLo.y);

    for (int c = 0; c < settings.cascades; ++c) {
        const double a = splits[size_t(c)], b = splits[size_t(c) + 1];
        if (visible && c + 1 < settings.cascades && b < visible->x) {
            out.dropped.push_back("cascade " + std::to_string(c + 1) + " (view depth " + rangeText(a, b) +
                                  ") is nearer than the visible scene (" + rangeText(visible->x, visible->y) + ")");
            continue;
        }
        if (visible && !out.cascades.empty() && a > visible->y) {
            out.cascades.back().splitFar = std::numeric_limits<float>::max();
            out.dropped.push_back("cascade" + std::string(settings.cascades - c > 1 ? "s " : " ") + std::to_string(c + 1) +
                                  (settings.cascades - c > 1 ? ".." + std::to_string(settings.cascades) : std::string()) +
                                  " (from view depth " + rangeText(a, splits.back()) + ") lie beyond the visible scene (" +
                                  rangeText(visible->x, visible->y) + ")");
            break;
        }
        // Smallest sphere around the slice's 8 corners: centre on the view axis at depth s.
        double s = std::clamp(0.5 * (a + b) * (1.0 + k2), a, b);
        const double radius = std::max(std::sqrt((s - a) * (s - a) + a * a * k2), std::sqrt((b - s) * (b - s) + b * b * k2));
        const glm::dvec3 centre = camPos + camForward * s;

        // Square side: the sphere's diameter, or the scene's light-space extent when smaller,
        // plus room for the origin snap below: (step + 1) texels, the step being --shadow-origin-step
        // of the tile (at least one texel). A square that spans the whole scene serves every depth
        // behind it too: it is the last cascade (the later ones would be identical tiles of the
        // same square, drawn for nothing).
        const bool coversScene = 2.0 * radius >= sceneSide;
        // Rounded up to a 2^(1/8) grid: a camera path that zooms (fov) or the split points' grid
        // changes the slice's sphere a little every frame; the square's size, and so its matrix,
        // changes only when the sphere crosses a step (at most 9% of resolution, 4.5% on average).
        const double exact = std::max(std::min(2.0 * radius, sceneSide), tiny);
        double needed = std::exp2(std::ceil(std::log2(exact) * 8.0) / 8.0);
        // --shadow-size-hold: last frame's side of this tile, while it holds the slice and wastes little.
        const size_t tile = out.cascades.size();
        if (settings.sizeHold && previous && tile < previous->cascades.size()) {
            const double held = previous->cascades[tile].side;
            if (held >= exact && held <= exact * kShadowSizeHoldRatio) needed = held;
        }
        const int stepTexels = originStepTexels(settings);
        const double texel = needed / double(settings.size - 1 - stepTexels);
        const double side = texel * settings.size, half = 0.5 * side, step = stepTexels * texel;

        // The origin: on a grid of `step` (whole texels), so it stays put while the camera moves
        // within a step and the cascade's tile (--shadow-cache) can be kept. Of the grid points
        // whose square holds the slice's sphere clipped to the scene's light-space bounds, the one
        // nearest the sphere's centre kept over the scene: a square pinned against the scene's edge,
        // or wider than the scene, does not move at all.
        const glm::dvec2 sphere(glm::dvec3(lightView * glm::dvec4(centre, 1.0)));
        glm::dvec2 ctr;
        for (int i = 0; i < 2; ++i) {
            const double nLo = std::min(std::max(sphere[i] - radius, lsLo[i]), lsHi[i]);
            const double nHi = std::max(std::min(sphere[i] + radius, lsHi[i]), nLo);
            const double slo = lsLo[i] + half, shi = lsHi[i] - half;
            const double want = std::clamp(slo <= shi ? std::clamp(sphere[i], slo, shi) : 0.5 * (lsLo[i] + lsHi[i]),
                                           nHi - half, nLo + half);
            const double below = std::floor(want / step) * step, above = below + step;
            const bool belowFits = below >= nHi - half, aboveFits = above <= nLo + half;
            ctr[i] = belowFits && (!aboveFits || want - below <= above - want) ? below : aboveFits ? above : want;
        }

        const glm::dmat4 proj = glm::ortho(ctr.x - 0.5 * side, ctr.x + 0.5 * side, ctr.y - 0.5 * side,
                                           ctr.y + 0.5 * side, nearZ, farZ);
        ShadowCascade cascade;
        cascade.worldToClip = toFloat(proj * lightView);
        cascade.eyeToClip = toFloat(proj * lightView * eyeToWorld);
        cascade.splitNear = float(a);
        const bool last = c + 1 == settings.cascades || coversScene;
        cascade.splitFar = last ? std::numeric_limits<float>::max() : float(b);
        cascade.texelWorld = float(texel);
        cascade.depthRange = float(farZ - nearZ);
        cascade.side = needed;
        cascade.tile = c;
        out.cascades.push_back(cascade);
        if (last) {
            if (c + 1 < settings.cascades)
                out.dropped.push_back("cascade" + std::string(settings.cascades - c > 2 ? "s " : " ") + std::to_string(c + 2) +
                                      (settings.cascades - c > 2 ? ".." + std::to_string(settings.cascades) : std::string()) +
                                      " of " + std::to_string(settings.cascades) + " dropped: cascade " + std::to_string(c + 1) +
                                      "'s square already covers the whole scene; later ones would be identical tiles");
            break;
        }
    }
    const glm::ivec2 used = shadowAtlasGrid(out.cascades.empty() ? 1 : out.cascades.back().tile + 1);
    out.columns = used.x;
    out.rows = used.y;
    return out;
}

std::string droppedCascadesReason(const ShadowFrustum& f, int requested) {
    if (int(f.cascades.size()) >= requested) return "";
    std::string why;
    for (const std::string& d : f.dropped) why += (why.empty() ? "" : "; ") + d;
    return why;
}

}  // namespace lp
