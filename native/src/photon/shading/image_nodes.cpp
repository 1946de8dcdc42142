#include "photon/shading/image_nodes.h"

#include <algorithm>
#include <cmath>

#include "photon/shading/textures.h"

namespace photon {
namespace {

enum ImageKind : uint16_t { kImage, kEnvironment };
enum Projection : uint32_t { kFlat, kBox, kSphere, kTube, kEquirect, kMirrorBall };

// Colour and alpha of texture `index` at `uv`; a texture that cannot be read is the fallback
// grey the add-on uses for missing images (alpha 1).
void lookup(const ShaderGlobals& g, int index, Vec2 uv, Vec3* color, float* alpha) {
  float rgba[4];
  if (g.textures && g.textures->lookup(index, uv, rgba)) {
    *color = Vec3(rgba[0], rgba[1], rgba[2]);
    *alpha = rgba[3];
    if (!is_finite(*color)) *color = Vec3(0.0f);
    if (!std::isfinite(*alpha)) *alpha = 0.0f;
  } else {
    *color = Vec3(0.8f);
    *alpha = 1.0f;
  }
}

// Cycles' map_to_sphere / map_to_tube of a point in [-1, 1]^3.
Vec2 map_to_sphere(const Vec3& d) {
  const float len = length(d);
  if (!(len > 0.0f)) return {0.0f, 0.0f};
  const float u = (d.x == 0.0f && d.y == 0.0f) ? 0.0f : (1.0f - std::atan2(d.x, d.y) / kPi) * 0.5f;
  const float v = 1.0f - std::acos(std::clamp(d.z / len, -1.0f, 1.0f)) / kPi;
  return {u, v};
}
Vec2 map_to_tube(const Vec3& d) {
  const float len = std::sqrt(d.x * d.x + d.y * d.y);
  if (!(len > 0.0f)) return {0.0f, 0.0f};
  return {(1.0f - std::atan2(d.x / len, d.y / len) / kPi) * 0.5f, (d.z + 1.0f) * 0.5f};
}

// Box projection (Cycles' svm_node_tex_image_box): the object-space normal picks the faces and
// `blend` widens the seams into cross-fades.
void box_lookup(const ShaderGlobals& g, int index, float blend, const Vec3& co, Vec3* color,
                float* alpha) {
  const Transform& m = g.object_to_world;
  Vec3 signed_n{m.m[0][0] * g.n.x + m.m[1][0] * g.n.y + m.m[2][0] * g.n.z,
                m.m[0][1] * g.n.x + m.m[1][1] * g.n.y + m.m[2][1] * g.n.z,
                m.m[0][2] * g.n.x + m.m[1][2] * g.n.y + m.m[2][2] * g.n.z};
  if (length_squared(signed_n) > 0.0f) signed_n = normalize(signed_n);
  Vec3 n{std::fabs(signed_n.x), std::fabs(signed_n.y), std::fabs(signed_n.z)};
  const float sum = n.x + n.y + n.z;
  if (sum > 0.0f) n = n / sum;
  Vec3 w(0.0f);
  const float limit = 0.5f * (1.0f + blend);
  if (n.x > limit * (n.x + n.y) && n.x > limit * (n.x + n.z)) {
    w.x = 1.0f;
  } else if (n.y > limit * (n.x + n.y) && n.y > limit * (n.y + n.z)) {
    w.y = 1.0f;
  } else if (n.z > limit * (n.x + n.z) && n.z > limit * (n.y + n.z)) {
    w.z = 1.0f;
  } else if (blend > 0.0f) {
    auto pair = [&](float a, float b, float* wa, float* wb) {
      float t = a / (a + b);
      t = std::clamp((t - 0.5f * (1.0f - blend)) / blend, 0.0f, 1.0f);
      *wa = t;
      *wb = 1.0f - t;
    };
    if (n.z < (1.0f - limit) * (n.y + n.x))
      pair(n.x, n.y, &w.x, &w.y);
    else if (n.x < (1.0f - limit) * (n.y + n.z))
      pair(n.y, n.z, &w.y, &w.z);
    else if (n.y < (1.0f - limit) * (n.x + n.z))
      pair(n.x, n.z, &w.x, &w.z);
    else
      w = (n * (2.0f - limit) + Vec3(limit - 1.0f)) / (2.0f * limit - 1.0f);
  } else {
    w.x = 1.0f;  // a normal exactly between faces with no blend
  }
  *color = Vec3(0.0f);
  *alpha = 0.0f;
  auto add = [&](float weight, Vec2 uv) {
    if (!(weight > 0.0f)) return;
    Vec3 c;
    float a;
    lookup(g, index, uv, &c, &a);
    *color += c * weight;
    *alpha += a * weight;
  };
  add(w.x, {signed_n.x < 0.0f ? 1.0f - co.y : co.y, co.z});
  add(w.y, {signed_n.y > 0.0f ? 1.0f - co.x : co.x, co.z});
  add(w.z, {signed_n.z > 0.0f ? 1.0f - co.y : co.y, co.x});
}

}  // namespace

Vec2 direction_to_equirectangular(const Vec3& d) {
  const float len = length(d);
  if (!(len > 0.0f)) return {0.5f, 0.5f};
  const float u = 0.5f - std::atan2(d.y, d.x) / (2.0f * kPi);
  const float v = 0.5f - (std::acos(std::clamp(d.z / len, -1.0f, 1.0f)) - 0.5f * kPi) / kPi;
  return {u, v};
}

Vec2 direction_to_mirror_ball(const Vec3& direction) {
  const float len = length(direction);
  if (!(len > 0.0f)) return {0.5f, 0.5f};
  Vec3 d = direction / len;
  d.y -= 1.0f;
  const float div = 2.0f * std::sqrt(std::max(-0.5f * d.y, 0.0f));
  if (div > 0.0f) d = d / div;
  return {0.5f * (d.x + 1.0f), 0.5f * (d.z + 1.0f)};
}

CompileStatus compile_image_node(const NodeDesc& desc, ShaderProgram*, Instruction* out,
                                 std::string* error) {
  const bool env = desc.type == "ShaderNodeTexEnvironment";
  if (desc.type != "ShaderNodeTexImage" && !env) return CompileStatus::kUnknownNode;
  out->family = NodeFamily::kImage;
  out->kind = env ? kEnvironment : kImage;
  out->in[0] = input_register(desc, "Vector");
  out->out[0] = output_register(desc, "Color");
  out->out[1] = output_register(desc, "Alpha");
  const double texture = number_value(desc, "texture", -1.0);
  out->param[0] = static_cast<float>(texture);  // -1: no readable image (fallback grey)
  if (out->in[0] < 0) {
    *error = desc.type + ": no texture coordinates";
    return CompileStatus::kError;
  }
  const std::string projection = enum_value(desc, "projection", env ? "EQUIRECTANGULAR" : "FLAT");
  if (env) {
    out->mode = projection == "MIRROR_BALL" ? kMirrorBall : kEquirect;
  } else if (projection == "BOX") {
    out->mode = kBox;
    out->param[1] =
        std::clamp(static_cast<float>(number_value(desc, "projection_blend", 0.0)), 0.0f, 1.0f);
  } else if (projection == "SPHERE") {
    out->mode = kSphere;
  } else if (projection == "TUBE") {
    out->mode = kTube;
  } else {
    out->mode = kFlat;
  }
  return CompileStatus::kCompiled;
}

void eval_image_node(const Instruction& ins, const ShaderProgram&, const ShaderGlobals& g,
                     float* r) {
  const int index = static_cast<int>(ins.param[0]);
  const Vec3 co = load3(r, ins.in[0]);
  Vec3 color;
  float alpha;
  switch (ins.mode) {
    case kBox:
      box_lookup(g, index, ins.param[1], co, &color, &alpha);
      break;
    case kSphere:
      lookup(g, index, map_to_sphere((co - Vec3(0.5f)) * 2.0f), &color, &alpha);
      break;
    case kTube:
      lookup(g, index, map_to_tube((co - Vec3(0.5f)) * 2.0f), &color, &alpha);
      break;
    case kEquirect:
      lookup(g, index, direction_to_equirectangular(co), &color, &alpha);
      break;
    case kMirrorBall:
      lookup(g, index, direction_to_mirror_ball(co), &color, &alpha);
      break;
    default:
      lookup(g, index, {co.x, co.y}, &color, &alpha);
      break;
  }
  store3(r, ins.out[0], color);
  store1(r, ins.out[1], alpha);
}

}  // namespace photon
