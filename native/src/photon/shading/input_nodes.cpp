#include "photon/shading/input_nodes.h"

#include <algorithm>
#include <cmath>

#include "photon/scene/scene.h"

namespace photon {
namespace {

enum InputKind : uint16_t {
  kTexCoord,
  kGeometry,
  kUvMap,
  kObjectInfo,
  kLightPath,
  kFresnel,
  kLayerWeight,
  kCameraData,
};

enum ConvertKind : uint16_t { kFloatToVector, kVectorToFloat, kColorToFloat, kBlockBegin };

// Output identifiers of each input node, in the order of Instruction::out (at most 5 per
// instruction: nodes with more outputs are split into several instructions by `part`).
struct OutputList {
  const char* type;
  InputKind kind;
  std::vector<const char*> outputs;
};

const std::vector<OutputList>& output_lists() {
  static const std::vector<OutputList> lists = {
      {"ShaderNodeTexCoord",
       kTexCoord,
       {"Generated", "Normal", "UV", "Object", "Camera", "Window", "Reflection"}},
      {"ShaderNodeNewGeometry",
       kGeometry,
       {"Position", "Normal", "Tangent", "True Normal", "Incoming", "Parametric", "Backfacing",
        "Pointiness", "Random Per Island"}},
      {"ShaderNodeUVMap", kUvMap, {"UV"}},
      {"ShaderNodeObjectInfo",
       kObjectInfo,
       {"Location", "Color", "Alpha", "Object Index", "Material Index", "Random"}},
      {"ShaderNodeLightPath",
       kLightPath,
       {"Is Camera Ray", "Is Shadow Ray", "Is Diffuse Ray", "Is Glossy Ray", "Is Singular Ray",
        "Is Reflection Ray", "Is Transmission Ray", "Ray Length", "Ray Depth", "Diffuse Depth",
        "Glossy Depth", "Transparent Depth", "Transmission Depth"}},
      {"ShaderNodeFresnel", kFresnel, {"Fac"}},
      {"ShaderNodeLayerWeight", kLayerWeight, {"Fresnel", "Facing"}},
      {"ShaderNodeCameraData", kCameraData, {"View Vector", "View Z Depth", "View Distance"}},
  };
  return lists;
}

Vec3 cycles_camera_point(const ShaderGlobals& g, const Vec3& p) {
  return g.world_to_camera.point(p);
}

Vec3 window_coordinates(const ShaderGlobals& g) {
  if (!g.camera) return Vec3(0.0f);
  const Camera& cam = *g.camera;
  const Vec3 c = g.world_to_camera.point(g.p);  // +Z forward
  float x = c.x, y = c.y;
  if (cam.projection == Projection::kPerspective) {
    if (!(c.z > 0.0f)) return Vec3(0.0f);
    x /= c.z;
    y /= c.z;
  }
  const float w = cam.window_max_x - cam.window_min_x, h = cam.window_max_y - cam.window_min_y;
  return {(x - cam.window_min_x) / w, (y - cam.window_min_y) / h, 0.0f};
}

Vec3 object_normal(const ShaderGlobals& g, const Vec3& n) {
  // The inverse of the normal matrix is the transpose of the object's 3x3.
  const Transform& m = g.object_to_world;
  const Vec3 o{m.m[0][0] * n.x + m.m[1][0] * n.y + m.m[2][0] * n.z,
               m.m[0][1] * n.x + m.m[1][1] * n.y + m.m[2][1] * n.z,
               m.m[0][2] * n.x + m.m[1][2] * n.y + m.m[2][2] * n.z};
  return length_squared(o) > 0.0f ? normalize(o) : o;
}

Vec3 normal_input(const Instruction& ins, int slot, const ShaderGlobals& g, const float* r) {
  return ins.in[slot] >= 0 ? load3(r, ins.in[slot]) : g.n;
}

void eval_tex_coord(const Instruction& ins, const ShaderProgram& program, const ShaderGlobals& g,
                    float* r) {
  if (g.is_background) {
    // Cycles' background: P is the direction, N and I point back along it.
    const Vec3 d = g.p;
    if (ins.mode != 0) {
      store3(r, ins.out[0], Vec3(0.0f));
      store3(r, ins.out[1], d);
      return;
    }
    store3(r, ins.out[0], d);
    store3(r, ins.out[1], -d);
    store3(r, ins.out[2], Vec3(0.0f));
    store3(r, ins.out[3],
           ins.data >= 0 ? Transform::from_rows(&program.data[ins.data]).vector(d) : d);
    return;
  }
  if (ins.mode == 0) {
    store3(r, ins.out[0], g.generated);
    store3(r, ins.out[1], object_normal(g, g.n));
    store3(r, ins.out[2], Vec3(g.uv.x, g.uv.y, 0.0f));
    // Object: this object's space, or that of the node's chosen object (its inverse matrix
    // in the table).
    store3(r, ins.out[3],
           ins.data >= 0 ? Transform::from_rows(&program.data[ins.data]).point(g.p)
                         : g.world_to_object.point(g.p));
    store3(r, ins.out[4], cycles_camera_point(g, g.p));
  } else {
    store3(r, ins.out[0], window_coordinates(g));
    // Reflection of the incoming direction about the shading normal, in world space.
    store3(r, ins.out[1], g.n * (2.0f * dot(g.n, g.incoming)) - g.incoming);
  }
}

void eval_geometry(const Instruction& ins, const ShaderGlobals& g, float* r) {
  if (ins.mode == 0) {
    store3(r, ins.out[0], g.p);
    store3(r, ins.out[1], g.n);
    Vec3 t(0.0f);
    if (length_squared(g.dpdu) > 0.0f) {
      t = g.dpdu - g.n * dot(g.n, g.dpdu);
      if (length_squared(t) > 0.0f) t = normalize(t);
    }
    store3(r, ins.out[2], t);
    store3(r, ins.out[3], g.ng);
    store3(r, ins.out[4], g.incoming);
  } else {
    store3(r, ins.out[0], Vec3(0.0f));  // Parametric: not known per triangle here
    store1(r, ins.out[1], g.backfacing ? 1.0f : 0.0f);
    store1(r, ins.out[2], 0.5f);  // Pointiness: flat (the add-on warns)
    store1(r, ins.out[3], 0.0f);  // Random Per Island (the add-on warns)
  }
}

void eval_light_path(const Instruction& ins, const ShaderGlobals& g, float* r) {
  const uint32_t f = g.ray_flags;
  auto flag = [&](uint32_t bit) { return (f & bit) ? 1.0f : 0.0f; };
  if (ins.mode == 0) {
    store1(r, ins.out[0], flag(kRayCamera));
    store1(r, ins.out[1], flag(kRayShadow));
    store1(r, ins.out[2], flag(kRayDiffuse));
    store1(r, ins.out[3], flag(kRayGlossy));
    store1(r, ins.out[4], flag(kRaySingular));
  } else if (ins.mode == 1) {
    store1(r, ins.out[0], flag(kRayReflect));
    store1(r, ins.out[1], flag(kRayTransmit));
    store1(r, ins.out[2], g.ray_length);
    store1(r, ins.out[3], g.ray_depth);
    store1(r, ins.out[4], g.diffuse_depth);
  } else {
    store1(r, ins.out[0], g.glossy_depth);
    store1(r, ins.out[1], g.transparent_depth);
    store1(r, ins.out[2], g.transmission_depth);
  }
}

}  // namespace

bool is_open_block_marker(const Instruction& ins) {
  return ins.family == NodeFamily::kConvert && ins.kind == kBlockBegin && ins.mode == 0;
}

float fresnel_dielectric_cos(float cosi, float eta) {
  const float c = std::fabs(cosi);
  float g = eta * eta - 1.0f + c * c;
  if (g > 0.0f) {
    g = std::sqrt(g);
    const float a = (g - c) / (g + c);
    const float b = (c * (g + c) - 1.0f) / (c * (g - c) + 1.0f);
    return 0.5f * a * a * (1.0f + b * b);
  }
  return 1.0f;  // total internal reflection
}

Transform inverse_affine(const Transform& t) {
  const float det = t.determinant3();
  if (!(std::fabs(det) > 1e-30f) || !std::isfinite(det)) return Transform();
  float n[3][3];
  t.normal_matrix(n);  // inverse transpose
  Transform inv;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) inv.m[i][j] = n[j][i];
  const Vec3 o = inv.vector(t.column(3));
  inv.m[0][3] = -o.x, inv.m[1][3] = -o.y, inv.m[2][3] = -o.z;
  return inv;
}

CompileStatus compile_input_node(const NodeDesc& desc, ShaderProgram* program, Instruction* out,
                                 std::string* error) {
  const OutputList* list = nullptr;
  for (const OutputList& l : output_lists())
    if (desc.type == l.type) list = &l;
  if (!list) return CompileStatus::kUnknownNode;
  out->family = NodeFamily::kInput;
  out->kind = list->kind;
  // Nodes with more than five outputs become one instruction per five; parts after the first,
  // when any of their outputs is used, go straight into the program (their order is free).
  for (size_t first = 5; first < list->outputs.size(); first += 5) {
    Instruction part = *out;
    part.mode = static_cast<uint32_t>(first / 5);
    bool used = false;
    for (size_t i = first; i < std::min(first + 5, list->outputs.size()); ++i) {
      part.out[i - first] = output_register(desc, list->outputs[i]);
      used |= part.out[i - first] >= 0;
    }
    if (used) program->code.push_back(part);
  }
  out->mode = 0;
  for (size_t i = 0; i < std::min<size_t>(5, list->outputs.size()); ++i)
    out->out[i] = output_register(desc, list->outputs[i]);
  switch (list->kind) {
    case kFresnel:
      out->in[0] = input_register(desc, "IOR");
      out->in[1] = input_register(desc, "Normal");
      break;
    case kLayerWeight:
      out->in[0] = input_register(desc, "Blend");
      out->in[1] = input_register(desc, "Normal");
      break;
    case kTexCoord:
      if (desc.table.size() == 12) {  // the chosen object's world-to-object matrix, by rows
        out->data = static_cast<int32_t>(program->data.size());
        out->data_size = 12;
        program->data.insert(program->data.end(), desc.table.begin(), desc.table.end());
      }
      break;
    default:
      break;
  }
  if ((list->kind == kFresnel || list->kind == kLayerWeight) && out->in[0] < 0) {
    *error = desc.type + ": its first input has no register";
    return CompileStatus::kError;
  }
  return CompileStatus::kCompiled;
}

void eval_input_node(const Instruction& ins, const ShaderProgram& program, const ShaderGlobals& g,
                     float* r) {
  switch (ins.kind) {
    case kTexCoord:
      eval_tex_coord(ins, program, g, r);
      break;
    case kGeometry:
      eval_geometry(ins, g, r);
      break;
    case kUvMap:
      store3(r, ins.out[0], Vec3(g.uv.x, g.uv.y, 0.0f));
      break;
    case kObjectInfo:
      if (ins.mode == 0) {
        store3(r, ins.out[0], g.object_location);
        store3(r, ins.out[1], g.object_color);
        store1(r, ins.out[2], g.object_alpha);
        store1(r, ins.out[3], g.object_pass_index);
        store1(r, ins.out[4], g.material_pass_index);
      } else {
        store1(r, ins.out[0], g.object_random);
      }
      break;
    case kLightPath:
      eval_light_path(ins, g, r);
      break;
    case kFresnel: {
      // Cycles' Fresnel node: the relative index flips on the back side.
      float eta = std::max(load1(r, ins.in[0]), 1e-5f);
      eta = g.backfacing ? 1.0f / eta : eta;
      const Vec3 n = normal_input(ins, 1, g, r);
      store1(r, ins.out[0], fresnel_dielectric_cos(dot(g.incoming, n), eta));
      break;
    }
    case kLayerWeight: {
      float blend = load1(r, ins.in[0]);
      const Vec3 n = normal_input(ins, 1, g, r);
      const float cosi = dot(g.incoming, n);
      float eta = std::max(1.0f - blend, 1e-5f);
      eta = g.backfacing ? eta : 1.0f / eta;
      store1(r, ins.out[0], fresnel_dielectric_cos(cosi, eta));
      float f = std::fabs(cosi);
      if (blend != 0.5f) {
        blend = std::clamp(blend, 0.0f, 1.0f - 1e-5f);
        blend = blend < 0.5f ? 2.0f * blend : 0.5f / (1.0f - blend);
        f = std::pow(f, blend);
      }
      store1(r, ins.out[1], 1.0f - f);
      break;
    }
    case kCameraData: {
      const Vec3 c = cycles_camera_point(g, g.p);
      const float d = length(c);
      store3(r, ins.out[0], d > 0.0f ? c / d : c);
      store1(r, ins.out[1], c.z);
      store1(r, ins.out[2], d);
      break;
    }
    default:
      break;
  }
}

CompileStatus compile_convert_node(const NodeDesc& desc, ShaderProgram*, Instruction* out,
                                   std::string* error) {
  ConvertKind kind;
  if (desc.type == "PhotonFloatToVector")
    kind = kFloatToVector;
  else if (desc.type == "PhotonVectorToFloat")
    kind = kVectorToFloat;
  else if (desc.type == "PhotonColorToFloat")
    kind = kColorToFloat;
  else if (desc.type == "PhotonBlockBegin")
    kind = kBlockBegin;
  else
    return CompileStatus::kUnknownNode;
  out->family = NodeFamily::kConvert;
  out->kind = kind;
  out->in[0] = input_register(desc, "In");
  out->out[0] = output_register(desc, "Out");
  if (kind == kBlockBegin) return CompileStatus::kCompiled;  // a marker: evaluates to nothing
  if (out->in[0] < 0) {
    *error = desc.type + " has no input register";
    return CompileStatus::kError;
  }
  return CompileStatus::kCompiled;
}

void eval_convert_node(const Instruction& ins, const ShaderProgram&, const ShaderGlobals&,
                       float* r) {
  switch (ins.kind) {
    case kFloatToVector:
      store3(r, ins.out[0], Vec3(load1(r, ins.in[0])));
      break;
    case kVectorToFloat: {
      const Vec3 v = load3(r, ins.in[0]);
      store1(r, ins.out[0], (v.x + v.y + v.z) * (1.0f / 3.0f));
      break;
    }
    case kColorToFloat:
      store1(r, ins.out[0], luminance(load3(r, ins.in[0])));
      break;
    default:
      break;
  }
}

}  // namespace photon
