// shade: texture lookup, latitude-longitude environment mapping and normal-map math, the scalar
// reference. Mirrored by texture_packet.h (same operations in the same order).
#pragma once

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace raylane {

namespace texture_detail {
inline constexpr float pi = 3.14159265358979323846f;
inline constexpr float two_pi = 6.28318530717958647692f;
/// dp/du is treated as parallel to n when its part perpendicular to n has a squared length at
/// most this fraction of |dp/du|^2 (an angle under about 0.06 degrees).
inline constexpr float tangent_parallel_fraction = 1e-6f;
/// A decoded normal of squared length below this is no direction: the map falls back to n.
inline constexpr float min_normal_length2 = 1e-12f;
/// keep_above leaves the bent normal at this cosine to the reference direction.
inline constexpr float keep_above_cos = 0.01f;
}  // namespace texture_detail

/// Colour of `t` at `uv`: (0, 0) is the bottom-left corner, v = 1 the top row of the file
/// (row 0 of Texture::texels), as in the report (report-scenes.md 1.6).
///
/// A NaN u or v gives black (every kind). Image textures: each coordinate is first wrapped
/// (`repeat`: c - floor(c) when c is outside [0, 1]; inside it is kept, so that v = 1 stays
/// the top row and the report's rule below is unchanged for its UVs) and then clamped to
/// [0, 1] (an infinite coordinate becomes 0 under repeat, 0 or 1 under clamp). Then:
/// - nearest: column round(u (W - 1)), row round((1 - v) (H - 1)), the report's rule;
/// - bilinear: texel centres at ((i + 1/2) / W, 1 - (j + 1/2) / H); the four texels around the
///   point, whose indices wrap round the edges under `repeat` and are clamped otherwise, are
///   blended by the fractional position (x first, then y). Under repeat u = 0 and u = 1 give
///   the same colour; under nearest they are the first and the last column (the seam).
/// An image with no texels (or fewer than width * height * 3) is black.
///
/// Checker: color_a where floor(u checks) + floor(v checks) is even, color_b where it is odd
/// (and where the sum is infinite). u, v are not wrapped: the pattern is infinite.
vec3 texture_lookup(const Texture& t, vec2 uv);

/// texture_lookup with each axis's wrap mode given instead of t.repeat (true = repeat).
vec3 texture_lookup(const Texture& t, vec2 uv, bool repeat_u, bool repeat_v);

/// The report's latitude-longitude mapping of a direction of any length:
///   u = (atan2(d_z, d_x) + pi) / (2 pi),  v = asin(d_y / |d|) / pi + 1/2.
/// Straight up (+y) is v = 1 (the top row), the horizon v = 1/2; -z is u = 1/4, +x u = 1/2,
/// +z u = 3/4, -x the seam (u = 1 or 0 for d_z = +0 or -0), and at the poles (d_x = d_z = 0)
/// u = 1/2. Robustness: d_y / |d| is taken
/// of d divided by its largest |component| (|d|^2 cannot overflow or underflow) and clamped
/// to [-1, 1]; u and v are clamped to [0, 1]. A zero or NaN direction, or one with an
/// infinite component, gives u = v = NaN (so black).
vec2 latlong_uv(vec3 dir);

/// texture_lookup(t, latlong_uv(dir), true, false): the wrap modes of a panorama, whatever
/// t.repeat says:
/// u repeats (bilinear blends across the seam at -x) and v clamps (a pole never blends with
/// the other pole). With the report's nearest rule this is the report's look-up exactly.
vec3 environment_lookup(const Texture& t, vec3 dir);

/// The shading normal given by a normal-map texel (RGB in [0, 1]) at a point with shading
/// normal n (normalized here), tangent dp/du and the mesh's normal_to_world matrix. Always a
/// unit vector (for a nonzero n).
/// - tangent: the frame T = normalize(dpdu - n (n . dpdu)) (Duff et al.'s branchless basis
///   vector when dp/du is zero, NaN or parallel to n: "Building an Orthonormal Basis,
///   Revisited", JCGT 2017), B = n x T, m = 2 texel - 1; result normalize(m.x T + m.y B +
///   m.z n). Green is +v (the OpenGL convention) when dp/dv points along n x dp/du; a mesh
///   whose uv layout is mirrored gets its green flipped (no bitangent sign is stored).
///   Texel (0.5, 0.5, 1) gives n.
/// - replace: the report's object-space mode: normalize(normal_to_world (texel - 1/2)).
/// A decoded vector of (near) zero length gives normalize(n) (numerics.md 13).
/// The result may face away from the geometric normal or the viewer: callers bend it with
/// keep_above and decide everything geometric (offsets, sides) with the geometric normal.
vec3 normal_from_map(NormalMapMode mode, vec3 texel, vec3 n, vec3 dpdu,
                     const glm::mat3& normal_to_world);

/// The shading normal ns (unit) bent into the hemisphere of the unit reference r: ns itself
/// when ns . r >= keep_above_cos (0.01), otherwise the unit vector in the plane of ns and r
/// whose cosine to r is exactly that: ns's part perpendicular to r, normalized, tilted up by
/// asin(0.01). r is the geometric normal, or the direction to the viewer to keep
/// ns . w_o > 0 (numerics.md 13). When ns is opposite to r (or NaN) the result is r.
vec3 keep_above(vec3 ns, vec3 r);

/// The shading normal ns (unit, above the unit geometric normal ng) turned towards the viewer
/// (wo, unit, on ng's side): ns itself when ns . wo >= keep_above_cos, otherwise normalize(ns +
/// lambda (ng - ns)) with lambda chosen so that the unnormalized cosine is keep_above_cos, or ng
/// itself (lambda = 1) when even ng . wo is below that (numerics.md 13: bend n_s toward n_g until
/// n_s . w_o is a small positive number). The result stays above ng.
vec3 face_viewer(vec3 ns, vec3 ng, vec3 wo);

}  // namespace raylane
