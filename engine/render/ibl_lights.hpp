#pragma once
// Small, very bright sources of an environment map (a sun, a lamp) taken out of the map at bake time
// and lit analytically (the way Frostbite, HDRP and Filament treat an HDRI's sun). A prefiltered
// chain and its round split-sum lobe lose a lamp of a few texels (-5..-9% on rough GGX spheres under
// a 50,000 lamp, bench/results/mitsuba/2026-11-24_ibl-against-mitsuba); a directional light evaluated with the BRDF itself
// does not. CPU, double precision, on the float equirectangular map before the cube, the prefiltered
// chain and the SH are made.
//
// A source is a connected region (8-neighbours, wrapping in longitude) of texels whose luminance is
// above `thresholdRatio` times the map's median luminance (median over solid angle: robust against
// the lamp itself and against a dark or a bright half), of at most kMaxLightSolidAngleFraction of the
// sphere. Its excess over the background (the mean of the texels around it) is removed from the map
// and becomes the light: the residual map's integral plus the lights' irradiance is the original's.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/io/image_io.hpp"

namespace lp {

// Largest source extracted: 0.5% of the sphere (a cap of 8.1 degrees radius). Anything wider is
// smooth enough for the prefiltered chain (its lobe is a few degrees at roughness 0.2).
constexpr double kMaxLightSolidAngleFraction = 0.005;
// Lights the shaders hold (shaders/common/ibl_shading.glsl LP_MAX_IBL_LIGHTS).
constexpr int kMaxEnvironmentLights = 4;

struct EnvironmentLight {
    glm::vec3 direction{0.0f, 1.0f, 0.0f};  // towards the source, world space (rotation applied), unit
    glm::vec3 irradiance{0.0f};             // E at normal incidence, RGB: sum of (L - background) dOmega
    float solidAngle = 0.0f;                // steradians of the region's texels
    float angularRadius = 0.0f;             // of the cap with that solid angle, radians
    int texels = 0;
};

struct LightExtraction {
    std::vector<EnvironmentLight> lights;  // brightest first
    double medianLuminance = 0.0;          // of the map, over solid angle
    double threshold = 0.0;                // luminance a texel must exceed
    int regions = 0;                       // regions above the threshold, before the cap and the count
    int tooLarge = 0;                      // of those, wider than kMaxLightSolidAngleFraction
    int leftInMap = 0;                     // of those, small but beyond maxLights
};

// Finds up to `maxLights` sources in `map` (RGBA float, equirectangular, v = 0 at +Y) and removes them
// from it. `rotationDegrees` about +Y as in projectEquirectSh. maxLights <= 0 or no region: nothing
// changes, the map is untouched.
LightExtraction extractEnvironmentLights(ImageF& map, double rotationDegrees, int maxLights, double thresholdRatio);

// One line per light ("light 1: direction (..), irradiance (..) W/m^2, 1.2e-05 sr (0.11 deg), 4 texels"),
// or one line saying why nothing was extracted.
std::vector<std::string> describeExtraction(const LightExtraction& e, int maxLights);

// Luminance (Rec. 709) used for the threshold.
inline double lightLuminance(glm::dvec3 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

}  // namespace lp
