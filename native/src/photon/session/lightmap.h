// Lightmaps from baked points (photon-mapped light turned into textures, filtered in 2D):
// texel centres are mapped to surface points through a UV layout, baked, then filtered in the
// texture plane with a filter that does not mix texels of different surfaces, and dilated into
// the gutters so bilinear lookups at chart borders do not read empty texels.
#pragma once

#include <cstdint>
#include <vector>

#include "photon/base/math.h"

namespace photon {

// A texel whose centre lies inside a UV triangle. Texel (x, y) has index y * width + x, with y
// upwards from v = 0 (Blender's image pixel order).
struct TexelPoint {
  uint32_t texel = 0;
  uint32_t triangle = 0;     // index of the UV triangle
  float u = 0.0f, v = 0.0f;  // barycentrics of corners 1 and 2 at the texel centre
  float world_size = 0.0f;   // edge length of one texel on the surface (from the triangle)
};

// Every texel centre covered by one of `triangle_count` UV triangles (uvs: 3 per triangle). A
// texel covered by several triangles (overlapping UVs) goes to the first. `positions` (3 per
// triangle, optional) give the world-space size of a texel; without them it is 0. Triangles
// with non-finite or degenerate UVs are skipped.
std::vector<TexelPoint> rasterize_uv_triangles(const Vec2* uvs, const Vec3* positions,
                                               size_t triangle_count, int width, int height);

struct LightmapFilter {
  int radius = 1;               // half-width of the filter window in texels (0 = no filtering)
  int dilate = 4;               // gutter texels filled around every chart
  float min_normal_cos = 0.9f;  // neighbours must face about the same way...
  float max_stretch = 1.5f;  // ...and lie within max_stretch * their texel distance on the surface
};

// Filters `values` (width * height) over the covered texels: a cone-weighted average (Jensen's
// cone filter, as the photon estimates use) of covered neighbours within `radius` that lie on
// the same surface, judged by normal and by 3D distance against texel distance (texels that
// are neighbours in UV space but not on the surface, like two charts packed side by side, do not
// mix). Then fills `dilate` rings of uncovered texels with the average of their covered
// 8-neighbours. Returns the new coverage in `covered_out` (may be null).
std::vector<Vec3> filter_lightmap(int width, int height, const std::vector<Vec3>& values,
                                  const std::vector<uint8_t>& covered,
                                  const std::vector<Vec3>& positions,
                                  const std::vector<Vec3>& normals,
                                  const std::vector<float>& world_size,
                                  const LightmapFilter& filter,
                                  std::vector<uint8_t>* covered_out = nullptr);

// Bilinear upsampling by an integer `factor` of a width x height image (texel centres kept
// aligned, edges clamped), written as RGBA with alpha 1 into `rgba` (factor^2 * width * height
// * 4 floats): a lightmap too large to shade texel by texel is shaded at a lower resolution,
// dilated, and upsampled into the image Blender keeps.
void upsample_lightmap_rgba(const Vec3* values, int width, int height, int factor, float* rgba);

}  // namespace photon
