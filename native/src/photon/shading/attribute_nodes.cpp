#include "photon/shading/attribute_nodes.h"

#include <cmath>

#include "photon/scene/mesh_attribute.h"

namespace photon {
namespace {

constexpr uint32_t kNoAttribute = 0xFFFFFFFFu;

}  // namespace

uint32_t program_attribute_slot(ShaderProgram* program, const std::string& name) {
  const uint64_t key = attribute_key(name);
  for (size_t i = 0; i < program->attributes.size(); ++i)
    if (program->attributes[i].key == key && program->attributes[i].name == name)
      return static_cast<uint32_t>(i);
  program->attributes.push_back({name, key});
  return static_cast<uint32_t>(program->attributes.size() - 1);
}

bool attribute_uv_tangents(const ShaderGlobals& g, const ShaderProgram& program, uint32_t slot,
                           Vec3* dpdu, Vec3* dpdv) {
  if (!g.mesh || slot >= program.attributes.size()) return false;
  const ProgramAttribute& wanted = program.attributes[slot];
  const MeshAttribute* a = find_mesh_attribute(*g.mesh, wanted.key, wanted.name);
  const size_t tri = g.primitive;
  if (!a || a->components < 2 || 3 * tri + 2 >= g.mesh->indices.size()) return false;
  const uint32_t* idx = &g.mesh->indices[3 * tri];
  const float* uv = &a->values[3 * tri * a->components];
  const uint32_t n = a->components;
  const Vec3 dp1 = g.mesh->positions[idx[1]] - g.mesh->positions[idx[0]];
  const Vec3 dp2 = g.mesh->positions[idx[2]] - g.mesh->positions[idx[0]];
  const float du1 = uv[n] - uv[0], dv1 = uv[n + 1] - uv[1];
  const float du2 = uv[2 * n] - uv[0], dv2 = uv[2 * n + 1] - uv[1];
  const float det = du1 * dv2 - dv1 * du2;
  if (!(std::fabs(det) > 1e-12f)) return false;
  *dpdu = g.object_to_world.vector((dp1 * dv2 - dp2 * dv1) / det);
  *dpdv = g.object_to_world.vector((dp2 * du1 - dp1 * du2) / det);
  return is_finite(*dpdu) && is_finite(*dpdv);
}

AttributeOutputs attribute_outputs(const float* v, uint32_t components, float missing_alpha) {
  AttributeOutputs o;
  switch (components) {
    case 1:
      o.vector = Vec3(v[0]);
      o.fac = v[0];
      o.alpha = 1.0f;
      break;
    case 2:  // a UV map or 2D vector: (x, y, 0), Fac its x
      o.vector = Vec3(v[0], v[1], 0.0f);
      o.fac = v[0];
      o.alpha = 1.0f;
      break;
    case 3:
    case 4:  // Fac the average of the three channels; only colours carry alpha
      o.vector = Vec3(v[0], v[1], v[2]);
      o.fac = (v[0] + v[1] + v[2]) * (1.0f / 3.0f);
      o.alpha = components == 4 ? v[3] : 1.0f;
      break;
    default:
      o.alpha = missing_alpha;
      break;
  }
  return o;
}

CompileStatus compile_attribute_node(const NodeDesc& desc, ShaderProgram* program, Instruction* out,
                                     std::string* error) {
  AttributeKind kind;
  if (desc.type == "ShaderNodeAttribute")
    kind = AttributeKind::kAttribute;
  else if (desc.type == "ShaderNodeVertexColor")
    kind = AttributeKind::kVertexColor;
  else if (desc.type == "ShaderNodeUVMap" && !enum_value(desc, "photon_attribute", "").empty())
    kind = AttributeKind::kUvMap;  // an unnamed UV Map reads the active map (input_nodes)
  else
    return CompileStatus::kUnknownNode;
  out->family = NodeFamily::kAttribute;
  out->kind = static_cast<uint16_t>(kind);
  const std::string name = enum_value(desc, "photon_attribute", "");
  // Cycles reads Object, Instancer and View Layer attributes from the object or the scene,
  // which Photon does not export: they read nothing (the add-on warns), all outputs 0.
  const bool geometry = kind != AttributeKind::kAttribute ||
                        enum_value(desc, "attribute_type", "GEOMETRY") == "GEOMETRY";
  out->mode = geometry && !name.empty() ? program_attribute_slot(program, name) : kNoAttribute;
  // A missing attribute's Alpha: Cycles gives 1 for the Attribute node's geometry attributes,
  // 0 for Color Attribute and the other attribute types.
  out->param[0] = kind == AttributeKind::kAttribute && geometry ? 1.0f : 0.0f;
  if (kind == AttributeKind::kUvMap) {
    out->out[0] = output_register(desc, "UV");
  } else if (kind == AttributeKind::kVertexColor) {
    out->out[0] = output_register(desc, "Color");
    out->out[3] = output_register(desc, "Alpha");
  } else {
    out->out[0] = output_register(desc, "Color");
    out->out[1] = output_register(desc, "Vector");
    out->out[2] = output_register(desc, "Fac");
    out->out[3] = output_register(desc, "Alpha");
  }
  (void)error;
  return CompileStatus::kCompiled;
}

void eval_attribute_node(const Instruction& ins, const ShaderProgram& program,
                         const ShaderGlobals& g, float* r) {
  float value[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  uint32_t components = 0;
  if (ins.mode < program.attributes.size() && g.mesh) {
    const ProgramAttribute& wanted = program.attributes[ins.mode];
    const MeshAttribute* a = find_mesh_attribute(*g.mesh, wanted.key, wanted.name);
    if (a && interpolate_attribute(*a, g.primitive, g.barycentric.x, g.barycentric.y, value))
      components = a->components;
  }
  const AttributeOutputs o = attribute_outputs(value, components, ins.param[0]);
  store3(r, ins.out[0], o.vector);
  store3(r, ins.out[1], o.vector);
  store1(r, ins.out[2], o.fac);
  store1(r, ins.out[3], o.alpha);
}

}  // namespace photon
