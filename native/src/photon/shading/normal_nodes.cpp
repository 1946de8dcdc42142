#include "photon/shading/normal_nodes.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "photon/scene/scene.h"
#include "photon/shading/attribute_nodes.h"
#include "photon/shading/input_nodes.h"
#include "photon/shading/node_registry.h"

namespace photon {
namespace {

enum NormalKind : uint16_t { kBump, kNormalMap };
enum NormalMapSpace : uint32_t { kTangent, kObject, kWorld, kBlenderObject, kBlenderWorld };

Vec3 mul3(const float m[3][3], const Vec3& v) {
  return Vec3(m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
              m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
              m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z);
}

Vec3 safe_normalize(const Vec3& v) {
  const float l2 = length_squared(v);
  return l2 > 0.0f && std::isfinite(l2) ? v / std::sqrt(l2) : Vec3(0.0f);
}

// Cycles' svm_node_set_bump and svm_node_bump: with dPdx, dPdy along the surface, the
// perturbed normal is normalize(|det| N - distance sign(det) (dhdx Rx + dhdy Ry)) where
// Rx = dPdy x N, Ry = N x dPdx, det = dPdx . Rx (Mikkelsen 2010, "Bump mapping unparametrized
// surfaces on the GPU", eq. 3), then blended towards N by strength.
void eval_bump(const Instruction& ins, const ShaderProgram& program, const ShaderGlobals& g,
               float* r, size_t index) {
  const Vec3 normal_in = ins.in[3] >= 0 ? safe_normalize(load3(r, ins.in[3])) : g.n;
  const float strength = std::clamp(load1(r, ins.in[0]), 0.0f, 1.0f);
  float distance = load1(r, ins.in[1]);
  if (ins.mode & 1u) distance = -distance;  // invert
  Vec3 result = normal_in;
  if (ins.skip > 0 && ins.in[2] >= 0 && strength > 0.0f && !g.is_background) {
    const float h_c = load1(r, ins.in[2]);
    const Frame frame(normal_in);
    const Vec3 dpdx = frame.t * g.bump_step, dpdy = frame.b * g.bump_step;
    // The height's nodes again, at the two offset points, on scratch copies of the registers
    // (the nodes' outputs at the shading point itself stay as they are for later readers).
    // One scratch buffer per thread (bumps nest only through their own blocks, which run on
    // a copy made here before the inner bump takes the buffer: each level copies first).
    thread_local std::vector<float> buffer;
    std::vector<float> scratch;
    scratch.swap(buffer);
    scratch.assign(r, r + program.registers.size());
    const size_t begin = index - static_cast<size_t>(ins.skip);
    run_block(program, begin, index, offset_globals(g, dpdx), scratch.data());
    const float h_x = scratch[ins.in[2]];
    std::copy(r, r + program.registers.size(), scratch.begin());
    run_block(program, begin, index, offset_globals(g, dpdy), scratch.data());
    const float h_y = scratch[ins.in[2]];
    scratch.swap(buffer);
    const Vec3 rx = cross(dpdy, normal_in), ry = cross(normal_in, dpdx);
    const float det = dot(dpdx, rx);
    const Vec3 surfgrad = rx * (h_x - h_c) + ry * (h_y - h_c);
    const float sign = det < 0.0f ? -1.0f : 1.0f;
    Vec3 n = safe_normalize(normal_in * std::fabs(det) - surfgrad * (distance * sign));
    if (length_squared(n) > 0.0f && std::isfinite(h_x) && std::isfinite(h_y))
      result = safe_normalize(n * strength + normal_in * (1.0f - strength));
    if (!(length_squared(result) > 0.0f)) result = normal_in;
  }
  store3(r, ins.out[0], result);
}

// Cycles' svm_node_normal_map: colour 2c - 1 in the tangent frame (T, sign B, N) of the
// interpolated normal, or in object / world space; then N + (N' - N) strength (Cycles 4.x: in
// tangent space Strength scales the colour's x, y and blends its z from 1 instead).
void eval_normal_map(const Instruction& ins, const ShaderProgram& program, const ShaderGlobals& g,
                     float* r) {
  const float strength = std::max(load1(r, ins.in[0]), 0.0f);
  Vec3 c = load3(r, ins.in[1]);
  c = Vec3(2.0f * (c.x - 0.5f), 2.0f * (c.y - 0.5f), 2.0f * (c.z - 0.5f));
  Vec3 n(0.0f);
  // Cycles 4.x applies Strength to a tangent-space colour before the frame (param[1] = 1).
  const bool tangent_strength = ins.mode == kTangent && ins.param[1] > 0.0f;
  if (tangent_strength) {
    const float raw = load1(r, ins.in[0]);
    const float t = std::clamp(raw, 0.0f, 1.0f);
    c = Vec3(c.x * raw, c.y * raw, 1.0f + t * (c.z - 1.0f));
  }
  if (ins.mode == kTangent) {
    // The node's named UV map (param[0] = its attribute slot + 1) or the active one.
    Vec3 dpdu = g.dpdu, dpdv = g.dpdv;
    if (ins.param[0] > 0.0f &&
        !attribute_uv_tangents(g, program, static_cast<uint32_t>(ins.param[0]) - 1, &dpdu, &dpdv))
      dpdu = dpdv = Vec3(0.0f);  // a missing map: the unperturbed normal, as in Cycles
    // Cycles combines the tangent frame in object space (where its tangent attribute and
    // the vertex normals live) and carries the result to world space as a normal: under a
    // non-uniform scale that differs from combining the world-space frame.
    float to_object_n[3][3], to_world_n[3][3];
    if (length_squared(dpdu) > 0.0f && g.world_to_object.normal_matrix(to_object_n) &&
        g.object_to_world.normal_matrix(to_world_n)) {
      const Vec3 n_obj = safe_normalize(mul3(to_object_n, g.n));
      const Vec3 dpdu_obj = g.world_to_object.vector(dpdu);
      const Vec3 dpdv_obj = g.world_to_object.vector(dpdv);
      Vec3 t = safe_normalize(dpdu_obj - n_obj * dot(n_obj, dpdu_obj));
      Vec3 b = cross(n_obj, t);
      if (dot(b, dpdv_obj) < 0.0f) b = -b;
      n = safe_normalize(mul3(to_world_n, t * c.x + b * c.y + n_obj * c.z));
    }
  } else {
    if (ins.mode == kBlenderObject || ins.mode == kBlenderWorld) c = Vec3(c.x, -c.y, -c.z);
    if (ins.mode == kObject || ins.mode == kBlenderObject) {
      float nm[3][3];
      if (g.object_to_world.normal_matrix(nm))
        c = Vec3(nm[0][0] * c.x + nm[0][1] * c.y + nm[0][2] * c.z,
                 nm[1][0] * c.x + nm[1][1] * c.y + nm[1][2] * c.z,
                 nm[2][0] * c.x + nm[2][1] * c.y + nm[2][2] * c.z);
    }
    n = safe_normalize(c);
    if (g.backfacing) n = -n;
  }
  if (length_squared(n) > 0.0f && strength != 1.0f && !tangent_strength)
    n = safe_normalize(g.n + (n - g.n) * strength);
  if (!(length_squared(n) > 0.0f)) n = g.n;
  store3(r, ins.out[0], n);
}

}  // namespace

ShaderGlobals offset_globals(const ShaderGlobals& g, const Vec3& dp) {
  ShaderGlobals s = g;
  s.p = g.p + dp;
  // Generated moves with the object-space offset scaled as the texture space scales it: the
  // ratio of Generated to object position per axis is constant on a mesh.
  const Vec3 obj_dp = g.world_to_object.vector(dp);
  s.generated = g.generated + obj_dp * g.generated_scale;
  // UV: solve dp = du dpdu + dv dpdv in the least-squares sense.
  const float a = dot(g.dpdu, g.dpdu), b = dot(g.dpdu, g.dpdv), c = dot(g.dpdv, g.dpdv);
  const float det = a * c - b * b;
  if (std::fabs(det) > 1e-30f) {
    const float pu = dot(dp, g.dpdu), pv = dot(dp, g.dpdv);
    s.uv = Vec2{g.uv.x + (c * pu - b * pv) / det, g.uv.y + (a * pv - b * pu) / det};
  }
  // Mesh attributes: the barycentrics move by the object-space offset written in the
  // triangle's edges (least squares, as for the UVs), extrapolating past its edges.
  if (g.mesh && 3 * static_cast<size_t>(g.primitive) + 2 < g.mesh->indices.size()) {
    const uint32_t* idx = &g.mesh->indices[3 * static_cast<size_t>(g.primitive)];
    const Vec3 e1 = g.mesh->positions[idx[1]] - g.mesh->positions[idx[0]];
    const Vec3 e2 = g.mesh->positions[idx[2]] - g.mesh->positions[idx[0]];
    const float a11 = dot(e1, e1), a12 = dot(e1, e2), a22 = dot(e2, e2);
    const float d = a11 * a22 - a12 * a12;
    if (std::fabs(d) > 1e-30f) {
      const float p1 = dot(obj_dp, e1), p2 = dot(obj_dp, e2);
      s.barycentric = Vec2{g.barycentric.x + (a22 * p1 - a12 * p2) / d,
                           g.barycentric.y + (a11 * p2 - a12 * p1) / d};
    }
  }
  return s;
}

CompileStatus compile_normal_node(const NodeDesc& desc, ShaderProgram* program, Instruction* out,
                                  std::string* error) {
  out->family = NodeFamily::kNormal;
  if (desc.type == "ShaderNodeBump") {
    out->kind = kBump;
    out->in[0] = input_register(desc, "Strength");
    out->in[1] = input_register(desc, "Distance");
    out->in[2] = input_register(desc, "Height");
    out->in[3] = input_register(desc, "Normal");
    out->out[0] = output_register(desc, "Normal");
    out->mode = enum_value(desc, "invert", "False") == "True" ? 1u : 0u;
    if (out->in[0] < 0 || out->in[1] < 0) {
      *error = "Bump: Strength and Distance need registers";
      return CompileStatus::kError;
    }
    // The height's code runs from the last open block marker up to this instruction (when the
    // add-on made a block: an unlinked Height has none).
    const bool block = number_value(desc, "block", 0.0) != 0.0;
    for (size_t i = program->code.size(); block && i-- > 0;) {
      if (is_open_block_marker(program->code[i])) {
        program->code[i].mode = 1;
        out->skip = static_cast<int32_t>(program->code.size() - i - 1);
        break;
      }
    }
    return CompileStatus::kCompiled;
  }
  if (desc.type == "ShaderNodeNormalMap") {
    out->kind = kNormalMap;
    out->in[0] = input_register(desc, "Strength");
    out->in[1] = input_register(desc, "Color");
    out->out[0] = output_register(desc, "Normal");
    const std::string space = enum_value(desc, "space", "TANGENT");
    out->mode = space == "OBJECT"           ? kObject
                : space == "WORLD"          ? kWorld
                : space == "BLENDER_OBJECT" ? kBlenderObject
                : space == "BLENDER_WORLD"  ? kBlenderWorld
                                            : kTangent;
    const std::string uv_map = enum_value(desc, "photon_attribute", "");
    if (out->mode == kTangent && !uv_map.empty())
      out->param[0] = static_cast<float>(program_attribute_slot(program, uv_map) + 1);
    // Blender 4.x (the add-on's enum "photon_cycles"): Strength acts in tangent space.
    if (enum_value(desc, "photon_cycles", "3") >= "4") out->param[1] = 1.0f;
    if (out->in[0] < 0 || out->in[1] < 0) {
      *error = "Normal Map: Strength and Color need registers";
      return CompileStatus::kError;
    }
    return CompileStatus::kCompiled;
  }
  return CompileStatus::kUnknownNode;
}

void eval_normal_node(const Instruction& ins, const ShaderProgram& program, const ShaderGlobals& g,
                      float* r) {
  if (ins.kind == kBump) {
    const size_t index = static_cast<size_t>(&ins - program.code.data());
    eval_bump(ins, program, g, r, index);
  } else {
    eval_normal_map(ins, program, g, r);
  }
}

}  // namespace photon
