// The visibility buffer (Burns & Hunt 2013): what gbuffer_visibility rasterises and how
// gbuffer_resolve turns it back into the triangle and the point on it.
// Id packing: id = the scene's global triangle index + 1 (0 = no geometry). The triangles are
// numbered draw by draw in SceneGpu order; each draw passes its first global triangle and adds
// gl_PrimitiveID (the triangle within the draw). 2^32 - 1 triangles fit.
#ifndef LP_VISIBILITY_GLSL
#define LP_VISIBILITY_GLSL

const uint LP_VISIBILITY_EMPTY = 0u;

uint visibilityPackId(uint drawFirstTriangle, uint primitiveId) { return drawFirstTriangle + primitiveId + 1u; }
// The global triangle of a non-empty id.
uint visibilityTriangle(uint id) { return id - 1u; }

// Barycentrics (w0, w1, w2) of the point where the ray origin + t dir meets the plane of triangle
// v0 v1 v2 (Möller-Trumbore without the inside test: the neighbouring pixels' rays of the UV
// derivatives may leave the triangle). They are the perspective-correct weights a rasteriser
// interpolates with at the pixel the ray goes through. Returns (1, 0, 0) for a ray parallel to the
// plane, which a ray through a rasterised pixel of the triangle never is.
vec3 rayTriangleBarycentrics(vec3 origin, vec3 dir, vec3 v0, vec3 v1, vec3 v2) {
    vec3 e1 = v1 - v0, e2 = v2 - v0;
    vec3 p = cross(dir, e2);
    float det = dot(e1, p);
    if (!(abs(det) > 0.0)) return vec3(1.0, 0.0, 0.0);
    float inv = 1.0 / det;
    vec3 t = origin - v0;
    float u = dot(t, p) * inv;
    vec3 q = cross(t, e1);
    float v = dot(dir, q) * inv;
    return vec3(1.0 - u - v, u, v);
}

// GL's perspective-correct interpolation weights at window position q of the triangle whose
// vertices lie at window positions s0, s1, s2 with clip w clipW: the 2-D barycentrics divided by w,
// normalised. With the rasteriser's snapped window positions it reproduces what a rasteriser that
// interpolates from its snapped vertices (engine/gl/raster_probe) gives the fragment at q.
vec3 windowBarycentrics(vec2 q, vec2 s0, vec2 s1, vec2 s2, vec3 clipW) {
    vec2 a = s0 - q, b = s1 - q, c = s2 - q;
    vec3 l = vec3(b.x * c.y - b.y * c.x, c.x * a.y - c.y * a.x, a.x * b.y - a.y * b.x) / clipW;
    float sum = l.x + l.y + l.z;
    return sum != 0.0 ? l / sum : vec3(1.0, 0.0, 0.0);
}

// The value at barycentrics b of an attribute whose vertices hold a0, a1, a2, in the rasteriser's
// plane-equation form a0 + b1 (a1 - a0) + b2 (a2 - a0): a value the three vertices share comes out
// exactly, so the points of a plane stay on it (a floor's eye z, a flat normal), as the raster's
// interpolated ones do. b0 a0 + b1 a1 + b2 a2 misses it by the weights' rounding (normalised, they sum
// to 1 only within a few ulps), which a light lying in the plane turns into N.L != 0.
float interpolateAttribute(vec3 b, float a0, float a1, float a2) { return a0 + b.y * (a1 - a0) + b.z * (a2 - a0); }
vec2 interpolateAttribute(vec3 b, vec2 a0, vec2 a1, vec2 a2) { return a0 + b.y * (a1 - a0) + b.z * (a2 - a0); }
vec3 interpolateAttribute(vec3 b, vec3 a0, vec3 a1, vec3 a2) { return a0 + b.y * (a1 - a0) + b.z * (a2 - a0); }
vec4 interpolateAttribute(vec3 b, vec4 a0, vec4 a1, vec4 a2) { return a0 + b.y * (a1 - a0) + b.z * (a2 - a0); }

// Whether the triangle v0 v1 v2 (eye space) faces the eye at the origin with counter-clockwise
// winding, i.e. gl_FrontFacing under a projection that does not mirror (GL_CCW front faces).
bool eyeTriangleFrontFacing(vec3 v0, vec3 v1, vec3 v2) { return dot(cross(v1 - v0, v2 - v0), v0) < 0.0; }

#endif
