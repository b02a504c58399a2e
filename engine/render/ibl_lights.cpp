#include "engine/render/ibl_lights.hpp"
#include "engine/render/ibl_sh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

namespace lp {

namespace {
constexpr double kPi = 3.14159265358979323846;

struct Region {
    std::vector<size_t> texels;  // y * width + x
    double solidAngle = 0.0;
    glm::dvec3 background{0.0};
    glm::dvec3 irradiance{0.0};
    glm::dvec3 weightedDirection{0.0};
};

glm::dvec3 texelRadiance(const ImageF& map, size_t i) {
    const float* p = &map.rgba[i * 4];
    return {p[0], p[1], p[2]};
}

std::string fmt(const char* format, double a, double b = 0.0, double c = 0.0) {
    char buf[128];
    std::snprintf(buf, sizeof buf, format, a, b, c);
    return buf;
}
}  // namespace

LightExtraction extractEnvironmentLights(ImageF& map, double rotationDegrees, int maxLights, double thresholdRatio) {
    LightExtraction out;
    const int w = map.width, h = map.height;
    if (maxLights <= 0 || w <= 0 || h <= 0) return out;
    const size_t n = size_t(w) * size_t(h);
    const double dPhi = 2.0 * kPi / w, dTheta = kPi / h;
    std::vector<double> rowSolidAngle(static_cast<size_t>(h));
    for (int y = 0; y < h; ++y) rowSolidAngle[size_t(y)] = dPhi * dTheta * std::sin((y + 0.5) / h * kPi);

    // Median luminance over solid angle, and the mean.
    std::vector<double> lum(n, 0.0);
    double total = 0.0, meanSum = 0.0;
    for (size_t i = 0; i < n; ++i) {
        lum[i] = lightLuminance(texelRadiance(map, i));
        total += rowSolidAngle[i / size_t(w)];
        meanSum += lum[i] * rowSolidAngle[i / size_t(w)];
    }
    std::vector<size_t> order(n);
    std::iota(order.begin(), order.end(), size_t(0));
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return lum[a] < lum[b]; });
    double acc = 0.0;
    for (size_t i : order) {
        acc += rowSolidAngle[i / size_t(w)];
        if (acc >= 0.5 * total) {
            out.medianLuminance = lum[i];
            break;
        }
    }
    // Where more than half the map is black the median is 0: 1% of the mean stands in for the level.
    const double level = std::max(out.medianLuminance, 0.01 * meanSum / total);
    out.threshold = thresholdRatio * level;

    // Regions: 8-connected texels above the threshold, wrapping in longitude.
    std::vector<int> label(n, -1);
    std::vector<Region> regions;
    std::vector<size_t> stack;
    auto neighbours = [&](size_t i, auto&& f) {
        const int x = int(i % size_t(w)), y = int(i / size_t(w));
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                if (!dx && !dy) continue;
                const int yy = y + dy;
                if (yy < 0 || yy >= h) continue;
                const int xx = (x + dx + w) % w;
                f(size_t(yy) * size_t(w) + size_t(xx));
            }
    };
    for (size_t seed = 0; seed < n; ++seed) {
        if (!(lum[seed] > out.threshold) || label[seed] >= 0) continue;
        const int id = int(regions.size());
        regions.emplace_back();
        Region& r = regions.back();
        label[seed] = id;
        stack.assign(1, seed);
        while (!stack.empty()) {
            const size_t i = stack.back();
            stack.pop_back();
            r.texels.push_back(i);
            r.solidAngle += rowSolidAngle[i / size_t(w)];
            neighbours(i, [&](size_t j) {
                if (label[j] < 0 && lum[j] > out.threshold) {
                    label[j] = id;
                    stack.push_back(j);
                }
            });
        }
    }
    out.regions = int(regions.size());

    // Per region: background = solid-angle mean of the texels around it; the excess over it is the light.
    const double rot = rotationDegrees * kPi / 180.0;
    std::vector<int> candidates;
    std::vector<char> inRing(n, 0);
    for (size_t id = 0; id < regions.size(); ++id) {
        Region& r = regions[id];
        if (r.solidAngle > kMaxLightSolidAngleFraction * 4.0 * kPi) {
            ++out.tooLarge;
            continue;
        }
        std::vector<size_t> ring;
        for (size_t i : r.texels)
            neighbours(i, [&](size_t j) {
                if (label[j] < 0 && !inRing[j]) {
                    inRing[j] = 1;
                    ring.push_back(j);
                }
            });
        glm::dvec3 sum(0.0);
        double ringAngle = 0.0;
        for (size_t j : ring) {
            sum += texelRadiance(map, j) * rowSolidAngle[j / size_t(w)];
            ringAngle += rowSolidAngle[j / size_t(w)];
            inRing[j] = 0;
        }
        r.background = ringAngle > 0.0 ? sum / ringAngle : glm::dvec3(0.0);
        for (size_t i : r.texels) {
            const glm::dvec3 L = texelRadiance(map, i);
            // The residual is stored as float: the excess is what the float leaves, so that residual +
            // light is the original to double precision.
            const glm::dvec3 kept = glm::dvec3(glm::vec3(glm::min(L, r.background)));
            const glm::dvec3 excess = L - kept;
            const double dOmega = rowSolidAngle[i / size_t(w)];
            r.irradiance += excess * dOmega;
            const double u = (double(i % size_t(w)) + 0.5) / w, v = (double(i / size_t(w)) + 0.5) / h;
            r.weightedDirection += rotateY(equirectDirection(u, v), rot) * (lightLuminance(excess) * dOmega);
        }
        if (lightLuminance(r.irradiance) > 0.0 && glm::length(r.weightedDirection) > 0.0)
            candidates.push_back(int(id));
    }
    std::sort(candidates.begin(), candidates.end(), [&](int a, int b) {
        return lightLuminance(regions[size_t(a)].irradiance) > lightLuminance(regions[size_t(b)].irradiance);
    });
    if (int(candidates.size()) > maxLights) {
        out.leftInMap = int(candidates.size()) - maxLights;
        candidates.resize(size_t(maxLights));
    }
    for (int id : candidates) {
        const Region& r = regions[size_t(id)];
        for (size_t i : r.texels) {
            float* p = &map.rgba[i * 4];
            for (int c = 0; c < 3; ++c) p[c] = std::min(p[c], float(r.background[c]));
        }
        EnvironmentLight light;
        light.direction = glm::vec3(glm::normalize(r.weightedDirection));
        light.irradiance = glm::vec3(r.irradiance);
        light.solidAngle = float(r.solidAngle);
        // Cap of the same solid angle: Omega = 2 pi (1 - cos theta).
        light.angularRadius = float(std::acos(std::clamp(1.0 - r.solidAngle / (2.0 * kPi), -1.0, 1.0)));
        light.texels = int(r.texels.size());
        out.lights.push_back(light);
    }
    return out;
}

std::vector<std::string> describeExtraction(const LightExtraction& e, int maxLights) {
    std::vector<std::string> lines;
    if (maxLights <= 0) return {"light extraction off (--ibl-extract-lights 0)"};
    if (e.lights.empty()) {
        std::string why = e.regions == 0 ? "no texel above " + fmt("%.4g", e.threshold) + " (the map's median " +
                                               fmt("%.4g", e.medianLuminance) + ")"
                                         : std::to_string(e.regions) + " region(s) above " + fmt("%.4g", e.threshold) +
                                               ", all wider than " + fmt("%.2g%%", kMaxLightSolidAngleFraction * 100.0) +
                                               " of the sphere";
        return {"no light extracted: " + why};
    }
    for (size_t i = 0; i < e.lights.size(); ++i) {
        const EnvironmentLight& l = e.lights[i];
        const glm::vec3 d = l.direction, E = l.irradiance;
        lines.push_back("light " + std::to_string(i + 1) + ": direction " + fmt("(%.3f, %.3f, ", d.x, d.y) +
                        fmt("%.3f), irradiance (%.4g, ", d.z, E.x) + fmt("%.4g, %.4g) W/m^2, ", E.y, E.z) +
                        fmt("%.3g sr (radius %.3g deg), ", l.solidAngle, l.angularRadius * 180.0 / kPi) +
                        std::to_string(l.texels) + " texels");
    }
    std::string tail = "above " + fmt("%.4g", e.threshold) + " (the map's median " + fmt("%.4g", e.medianLuminance) + ")";
    if (e.tooLarge) tail += "; " + std::to_string(e.tooLarge) + " wider region(s) left in the map";
    if (e.leftInMap) tail += "; " + std::to_string(e.leftInMap) + " more left in the map (--ibl-extract-lights)";
    lines.push_back(tail);
    return lines;
}

}  // namespace lp
