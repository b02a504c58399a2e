#include "engine/render/ibl_sh.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace lp {

namespace {
constexpr double kPi = 3.14159265358979323846;

// Visits every texel with its world direction, solid angle and radiance. A texel's direction is
// rotateY(equirectDirection(u, v), a): sin(theta) times its column's direction on the equator, plus
// cos(theta) up, so a table per column (and the row's sin and cos) replaces the trig per texel.
template <typename F>
void forEachTexel(const ImageF& map, double rotationDegrees, F&& f) {
    const double rot = rotationDegrees * kPi / 180.0;
    const double dPhi = 2.0 * kPi / map.width, dTheta = kPi / map.height;
    std::vector<double> sinPhi(size_t(map.width)), cosPhi(size_t(map.width));
    for (int x = 0; x < map.width; ++x) {
        const glm::dvec3 equator = rotateY(equirectDirection((x + 0.5) / map.width, 0.5), rot);
        sinPhi[size_t(x)] = equator.x;
        cosPhi[size_t(x)] = -equator.z;
    }
    for (int y = 0; y < map.height; ++y) {
        const double theta = (y + 0.5) / map.height * kPi;
        const double sinT = std::sin(theta), cosT = std::cos(theta);
        const double solidAngle = dPhi * dTheta * sinT;
        const float* row = &map.rgba[size_t(y) * size_t(map.width) * 4];
        for (int x = 0; x < map.width; ++x) {
            const float* px = row + size_t(x) * 4;
            f(glm::dvec3(sinT * sinPhi[size_t(x)], cosT, -sinT * cosPhi[size_t(x)]), solidAngle,
              glm::dvec3(px[0], px[1], px[2]));
        }
    }
}
}  // namespace

glm::dvec3 equirectDirection(double u, double v) {
    const double phi = (u - 0.5) * 2.0 * kPi, theta = v * kPi;
    return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

glm::dvec3 rotateY(glm::dvec3 d, double radians) {
    const double c = std::cos(radians), s = std::sin(radians);
    return {c * d.x + s * d.z, d.y, -s * d.x + c * d.z};
}

std::array<double, 9> shBasis(glm::dvec3 d) {
    return {0.282095,
            0.488603 * d.y,
            0.488603 * d.z,
            0.488603 * d.x,
            1.092548 * d.x * d.y,
            1.092548 * d.y * d.z,
            0.315392 * (3.0 * d.z * d.z - 1.0),
            1.092548 * d.x * d.z,
            0.546274 * (d.x * d.x - d.y * d.y)};
}

ShCoefficients projectEquirectSh(const ImageF& map, double rotationDegrees) {
    ShCoefficients sh{};
    forEachTexel(map, rotationDegrees, [&](glm::dvec3 d, double dOmega, glm::dvec3 radiance) {
        const auto y = shBasis(d);
        for (int i = 0; i < 9; ++i) sh[size_t(i)] += radiance * (y[size_t(i)] * dOmega);
    });
    return sh;
}

glm::dvec3 shIrradiance(const ShCoefficients& sh, glm::dvec3 n) {
    const double band[9] = {kPi, 2.0 * kPi / 3.0, 2.0 * kPi / 3.0, 2.0 * kPi / 3.0, kPi / 4.0,
                            kPi / 4.0, kPi / 4.0, kPi / 4.0, kPi / 4.0};
    const auto y = shBasis(n);
    glm::dvec3 e(0.0);
    for (int i = 0; i < 9; ++i) e += sh[size_t(i)] * (band[i] * y[size_t(i)]);
    return glm::max(e, glm::dvec3(0.0));
}

glm::dvec3 bruteForceIrradiance(const ImageF& map, double rotationDegrees, glm::dvec3 n) {
    glm::dvec3 e(0.0);
    forEachTexel(map, rotationDegrees, [&](glm::dvec3 d, double dOmega, glm::dvec3 radiance) {
        const double c = glm::dot(d, n);
        if (c > 0.0) e += radiance * (c * dOmega);
    });
    return e;
}

}  // namespace lp
