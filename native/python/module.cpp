// The `_photon` Python module: builds a native Scene from numpy buffers and runs renders with the
// GIL released. Blender types never reach this file; the add-on converts them to arrays first.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstring>
#include <stdexcept>

#include "data_pass_bindings.h"
#include "material_binding.h"
#include "photon/integrators/registry.h"
#include "photon/integrators/render_params.h"
#include "photon/scene/mesh_attribute.h"
#include "photon/scene/mesh_import.h"
#include "photon/scene/scene.h"
#include "photon/scene/vertex_normals.h"
#include "photon/session/render_session.h"
#include "photon/shading/program_eval.h"
#include "photon/shading/texture_convert.h"
#include "photon/spectral/dispersion.h"
#include "program_binding.h"
#include "sppm_bindings.h"
#include "stats_bindings.h"

namespace py = pybind11;
using namespace photon;

void bind_bake(py::module_& m);         // bake_bindings.cpp
void bind_persistent(py::module_& m);   // persistent_bindings.cpp
void bind_progressive(py::module_& m);  // progressive_bindings.cpp

namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;
using IntArray = py::array_t<int32_t, py::array::c_style | py::array::forcecast>;

// Copies a numpy array holding `group` values per row into `out` with one memcpy; each element of
// `out` packs sizeof(T) / sizeof(value) values (a Vec3 packs three floats).
template <typename T, typename Array>
void copy_rows(const Array& a, size_t group, std::vector<T>* out, const char* what) {
  using Value = typename Array::value_type;
  static_assert(sizeof(T) % sizeof(Value) == 0, "element layout");
  constexpr size_t kPerElement = sizeof(T) / sizeof(Value);
  const size_t n = static_cast<size_t>(a.size());
  if (n % group != 0 || n % kPerElement != 0)
    throw std::invalid_argument(std::string(what) + ": size is not a multiple of " +
                                std::to_string(group));
  // One spare element: Embree may then share a mesh's vertex array instead of copying it
  // (its 16-byte loads read 4 bytes past the last vertex; accel.cpp).
  out->reserve(n / kPerElement + 1);
  out->resize(n / kPerElement);
  if (n) std::memcpy(out->data(), a.data(), n * sizeof(Value));
}

Transform transform_from(const FloatArray& m) {
  if (m.size() != 16 && m.size() != 12)
    throw std::invalid_argument("matrix must have 16 (4x4) or 12 (3x4) values, row-major");
  return Transform::from_rows(m.data());
}

Vec3 vec3_from(const std::vector<float>& v, const char* what) {
  if (v.size() < 3) throw std::invalid_argument(std::string(what) + " needs 3 values");
  return {v[0], v[1], v[2]};
}

// Drops invalid triangles (without the GIL) and appends the mesh; returns what happened.
py::dict finish_mesh(Scene& scene, Mesh&& mesh) {
  MeshCleanupReport report;
  {
    py::gil_scoped_release release;
    report = clean_mesh(&mesh);
    snap_normals(&mesh);
  }
  py::dict d;
  d["index"] = scene.meshes.size();
  d["triangles"] = mesh.triangle_count();
  d["non_finite_vertices"] = report.non_finite_vertices;
  d["dropped_triangles"] = report.dropped_triangles;
  scene.meshes.push_back(std::move(mesh));
  return d;
}

template <typename Array>
const typename Array::value_type* optional_data(const py::object& obj, Array* holder, size_t group,
                                                size_t count, const char* what) {
  if (obj.is_none()) return nullptr;
  *holder = obj.cast<Array>();
  if (static_cast<size_t>(holder->size()) != group * count)
    throw std::invalid_argument(std::string(what) + ": expected " + std::to_string(group * count) +
                                " values");
  return holder->data();
}

py::array_t<float> to_numpy(std::vector<float>&& data, int height, int width) {
  auto* heap = new std::vector<float>(std::move(data));
  py::capsule owner(heap, [](void* p) { delete static_cast<std::vector<float>*>(p); });
  return py::array_t<float>({height, width, 4}, heap->data(), owner);
}

// Every schema'd parameter as a property of RenderSettings, typed as in the schema: ints, floats,
// bools, and the Integrator enum (set from the enum or from an item id such as "RADIOSITY").
// Values are stored as given; the render session clamps them with a warning.
void bind_render_params(py::class_<RenderSettings>& cls) {
  for (const RenderParamGroup& group : render_param_groups()) {
    for (const RenderParam& p : group.params) {
      const RenderParam* param = &p;
      cls.def_property(
          p.spec->name.c_str(),
          [param](const RenderSettings& s) -> py::object {
            const double v = param->get(s);
            switch (param->spec->type) {
              case ParamType::kBool:
                return py::bool_(v != 0.0);
              case ParamType::kFloat:
                return py::float_(v);
              case ParamType::kEnum:
                if (param->spec->name == "integrator")
                  return py::cast(static_cast<IntegratorType>(static_cast<int>(v)));
                for (const ParamEnumItem& item : param->spec->items)  // other enums: item id
                  if (item.value == static_cast<int>(v)) return py::str(item.id);
                return py::none();
              case ParamType::kUInt64:
                return py::int_(static_cast<unsigned long long>(v));
              case ParamType::kInt:
                break;
            }
            return py::int_(static_cast<long long>(v));
          },
          [param](RenderSettings& s, const py::object& value) {
            const ParamSpec& spec = *param->spec;
            if (spec.type == ParamType::kEnum) {
              if (py::isinstance<py::str>(value)) {
                const std::string id = value.cast<std::string>();
                for (const ParamEnumItem& item : spec.items)
                  if (item.id == id) return param->set(s, item.value);
                throw py::value_error(spec.name + ": no item '" + id + "'");
              }
              if (spec.name != "integrator") throw py::value_error(spec.name + ": give an item id");
              return param->set(s, static_cast<int>(value.cast<IntegratorType>()));
            }
            param->set(s, value.cast<double>());
          });
    }
  }
}

}  // namespace

PYBIND11_MODULE(_photon, m) {
  m.doc() = "Photon native renderer";

  py::class_<Scene, std::shared_ptr<Scene>>(m, "Scene")
      .def(py::init<>())
      .def(
          "add_mesh",
          [](Scene& scene, const std::string& name, const FloatArray& positions,
             const IntArray& triangles, py::object corner_normals, py::object corner_uvs,
             py::object material_slots) {
            Mesh mesh;
            mesh.name = name;
            copy_rows(positions, 3, &mesh.positions, "positions");
            // Reinterpreted as unsigned: a negative index becomes huge and is dropped as out of
            // range.
            copy_rows(triangles, 3, &mesh.indices, "triangles");
            if (!corner_normals.is_none())
              copy_rows(corner_normals.cast<FloatArray>(), 3, &mesh.corner_normals,
                        "corner_normals");
            if (!corner_uvs.is_none())
              copy_rows(corner_uvs.cast<FloatArray>(), 2, &mesh.corner_uvs, "corner_uvs");
            if (!material_slots.is_none())
              copy_rows(material_slots.cast<IntArray>(), 1, &mesh.material_slots, "material_slots");
            return finish_mesh(scene, std::move(mesh));
          },
          py::arg("name"), py::arg("positions"), py::arg("triangles"),
          py::arg("corner_normals") = py::none(), py::arg("corner_uvs") = py::none(),
          py::arg("material_slots") = py::none(),
          "Adds a triangle mesh; invalid triangles are dropped and counted.")
      .def(
          "add_loop_mesh",
          [](Scene& scene, const std::string& name, const FloatArray& positions,
             const IntArray& corner_loops, const IntArray& loop_vertices, py::object vertex_normals,
             py::object loop_normals, py::object loop_uvs, py::object material_slots,
             py::object poly_loop_starts, py::object poly_loop_totals, py::object poly_smooth) {
            Mesh mesh;
            mesh.name = name;
            copy_rows(positions, 3, &mesh.positions, "positions");
            if (corner_loops.size() % 3)
              throw std::invalid_argument("corner_loops: 3 per triangle");
            LoopMeshView view;
            view.corner_loops = corner_loops.data();
            view.corner_count = corner_loops.size();
            view.loop_vertices = loop_vertices.data();
            view.loop_count = loop_vertices.size();
            FloatArray vn, ln, uv;
            view.vertex_normals =
                optional_data(vertex_normals, &vn, 3, mesh.positions.size(), "vertex_normals");
            view.loop_normals =
                optional_data(loop_normals, &ln, 3, view.loop_count, "loop_normals");
            view.loop_uvs = optional_data(loop_uvs, &uv, 2, view.loop_count, "loop_uvs");
            if (poly_loop_starts.is_none() != poly_loop_totals.is_none())
              throw std::invalid_argument("poly_loop_starts and poly_loop_totals go together");
            IntArray starts, totals;
            using FlagArray = py::array_t<uint8_t, py::array::c_style | py::array::forcecast>;
            FlagArray smooth;
            if (!poly_loop_starts.is_none()) {
              starts = poly_loop_starts.cast<IntArray>();
              totals = poly_loop_totals.cast<IntArray>();
              if (starts.size() != totals.size())
                throw std::invalid_argument("poly_loop_starts and poly_loop_totals differ in size");
              if (!poly_smooth.is_none()) {
                smooth = poly_smooth.cast<FlagArray>();
                if (smooth.size() != starts.size())
                  throw std::invalid_argument("poly_smooth: one flag per polygon");
              }
            }
            std::vector<Vec3> vertex_normals_here, loop_normals_here;
            {
              py::gil_scoped_release release;
              // Shading normals from the polygons when Blender's own normals are not given.
              if (!view.vertex_normals && !view.loop_normals && starts.size()) {
                PolygonMeshView polygons{mesh.positions.data(),
                                         mesh.positions.size(),
                                         view.loop_vertices,
                                         view.loop_count,
                                         starts.data(),
                                         totals.data(),
                                         static_cast<size_t>(starts.size())};
                vertex_normals_here = angle_weighted_vertex_normals(polygons);
                if (smooth.size()) {
                  loop_normals_here =
                      smooth_and_flat_loop_normals(polygons, smooth.data(), vertex_normals_here);
                  view.loop_normals = reinterpret_cast<const float*>(loop_normals_here.data());
                } else {
                  view.vertex_normals = reinterpret_cast<const float*>(vertex_normals_here.data());
                }
              }
              gather_loop_mesh(view, &mesh);
            }
            if (!material_slots.is_none())
              copy_rows(material_slots.cast<IntArray>(), 1, &mesh.material_slots, "material_slots");
            return finish_mesh(scene, std::move(mesh));
          },
          py::arg("name"), py::arg("positions"), py::arg("corner_loops"), py::arg("loop_vertices"),
          py::arg("vertex_normals") = py::none(), py::arg("loop_normals") = py::none(),
          py::arg("loop_uvs") = py::none(), py::arg("material_slots") = py::none(),
          py::arg("poly_loop_starts") = py::none(), py::arg("poly_loop_totals") = py::none(),
          py::arg("poly_smooth") = py::none(),
          "Adds a mesh given as Blender stores it: three loop indices per triangle, the vertex "
          "of each loop, and per-vertex or per-loop normals and per-loop UVs. With the polygons "
          "(each one's first loop and loop count) and no normals, the mesh is smooth shaded "
          "with angle-weighted vertex normals computed here, the same on every run; with "
          "poly_smooth too, polygons whose flag is 0 are flat shaded.")
      .def(
          "add_instance",
          [](Scene& scene, uint32_t mesh, const FloatArray& matrix,
             const std::vector<int32_t>& slot_materials, uint32_t visibility,
             const std::string& name, bool holdout, bool shadow_catcher) {
            if (mesh >= scene.meshes.size()) throw std::out_of_range("mesh index");
            Instance inst;
            inst.name = name;
            inst.mesh = mesh;
            inst.object_to_world = transform_from(matrix);
            inst.slot_materials = slot_materials;
            inst.visibility = visibility & kVisibleAll;
            inst.holdout = holdout;
            inst.shadow_catcher = shadow_catcher;
            scene.instances.push_back(std::move(inst));
            return scene.instances.size() - 1;
          },
          py::arg("mesh"), py::arg("matrix"), py::arg("slot_materials") = std::vector<int32_t>{},
          py::arg("visibility") = static_cast<uint32_t>(kVisibleAll), py::arg("name") = "",
          py::arg("holdout") = false, py::arg("shadow_catcher") = false)
      .def(
          "add_instances",
          [](Scene& scene, uint32_t mesh, const FloatArray& matrices,
             const std::vector<int32_t>& slot_materials, uint32_t visibility,
             const std::string& name, bool holdout, bool shadow_catcher) {
            if (mesh >= scene.meshes.size()) throw std::out_of_range("mesh index");
            if (matrices.size() % 16) throw std::invalid_argument("matrices: N x 4 x 4 expected");
            const size_t n = matrices.size() / 16;
            for (size_t i = 0; i < n; ++i) {
              Instance inst;
              inst.name = name;
              inst.mesh = mesh;
              inst.object_to_world = Transform::from_rows(matrices.data() + 16 * i);
              inst.slot_materials = slot_materials;
              inst.visibility = visibility & kVisibleAll;
              inst.holdout = holdout;
              inst.shadow_catcher = shadow_catcher;
              scene.instances.push_back(std::move(inst));
            }
            return n;
          },
          py::arg("mesh"), py::arg("matrices"), py::arg("slot_materials") = std::vector<int32_t>{},
          py::arg("visibility") = static_cast<uint32_t>(kVisibleAll), py::arg("name") = "",
          py::arg("holdout") = false, py::arg("shadow_catcher") = false,
          "Adds many instances of one mesh from an (N, 4, 4) array of row-major matrices.")
      .def(
          "add_mesh_attribute",
          [](Scene& scene, uint32_t mesh, const std::string& name, const FloatArray& values) {
            if (mesh >= scene.meshes.size()) throw std::out_of_range("mesh index");
            if (values.ndim() != 2) throw std::invalid_argument("values: (corners, components)");
            std::string error;
            if (!add_mesh_attribute(&scene.meshes[mesh], name,
                                    static_cast<uint32_t>(values.shape(1)), values.data(),
                                    static_cast<size_t>(values.size()), &error))
              throw std::invalid_argument(error);
          },
          py::arg("mesh"), py::arg("name"), py::arg("values"),
          "Adds a named attribute shader programs read (Attribute, Color Attribute, UV Map "
          "nodes): a (3 x triangles, 1..4) float array, three corners per triangle in the order "
          "the mesh's triangles were given (point and face values expanded to corners).")
      .def(
          "set_mesh_texspace",
          [](Scene& scene, uint32_t mesh, const std::vector<float>& location,
             const std::vector<float>& size) {
            if (mesh >= scene.meshes.size()) throw std::out_of_range("mesh index");
            const Vec3 loc = vec3_from(location, "location"), sz = vec3_from(size, "size");
            if (is_finite(loc) && is_finite(sz)) {
              scene.meshes[mesh].texspace_location = loc;
              scene.meshes[mesh].texspace_size = sz;
            }
          },
          py::arg("mesh"), py::arg("location"), py::arg("size"),
          "Sets a mesh's texture space (Generated coordinates), Blender's texspace_location/size.")
      .def(
          "set_instance_info",
          [](Scene& scene, size_t first, const std::vector<float>& color,
             const std::vector<float>& randoms, float pass_index, float alpha) {
            const Vec3 c = vec3_from(color, "color");
            if (first + randoms.size() > scene.instances.size())
              throw std::out_of_range("instance index");
            for (size_t i = 0; i < randoms.size(); ++i) {
              Instance& inst = scene.instances[first + i];
              inst.color = is_finite(c) ? c : Vec3(1.0f);
              inst.random = std::isfinite(randoms[i]) ? std::clamp(randoms[i], 0.0f, 1.0f) : 0.0f;
              inst.pass_index = std::isfinite(pass_index) ? pass_index : 0.0f;
              inst.alpha = std::isfinite(alpha) ? alpha : 1.0f;
            }
          },
          py::arg("first"), py::arg("color"), py::arg("randoms"), py::arg("pass_index") = 0.0f,
          py::arg("alpha") = 1.0f,
          "Object Info of instances first .. first + len(randoms): colour, random, pass index, "
          "alpha (the object colour's fourth channel).")
      .def(
          "set_instance_cryptomatte",
          [](Scene& scene, size_t first, const std::vector<float>& object_ids,
             const std::vector<float>& asset_ids) {
            if (asset_ids.size() != object_ids.size())
              throw py::value_error("object_ids and asset_ids differ in length");
            if (first + object_ids.size() > scene.instances.size())
              throw std::out_of_range("instance index");
            for (size_t i = 0; i < object_ids.size(); ++i) {
              scene.instances[first + i].cryptomatte_object = object_ids[i];
              scene.instances[first + i].cryptomatte_asset = asset_ids[i];
            }
          },
          py::arg("first"), py::arg("object_ids"), py::arg("asset_ids"),
          "Cryptomatte object and asset IDs (floats made from name hashes) of instances first "
          ".. first + len(object_ids).")
      .def(
          "set_material_cryptomatte",
          [](Scene& scene, size_t material, float id) {
            if (material >= scene.materials.size()) throw std::out_of_range("material index");
            scene.materials[material].cryptomatte_material = id;
          },
          py::arg("material"), py::arg("id"),
          "A material's Cryptomatte ID (a float made from its name's hash).")
      .def(
          "add_texture",
          [](Scene& scene, const std::string& path, bool srgb, const std::string& extension,
             const std::string& interpolation, const std::string& alpha, bool unassociate) {
            ImageTexture t = photon_python::parse_texture(path, srgb, extension, interpolation);
            photon_python::parse_texture_alpha(&t, alpha, unassociate);
            scene.textures.push_back(std::move(t));
            return scene.textures.size() - 1;
          },
          py::arg("path"), py::arg("srgb") = true, py::arg("extension") = "REPEAT",
          py::arg("interpolation") = "Linear", py::arg("alpha") = "KEEP",
          py::arg("unassociate") = false,
          "Adds an image file (an Image Texture node's image and sampling); returns its index.")
      .def(
          "add_texture_pixels",
          [](Scene& scene, std::shared_ptr<TexturePixels> pixels, const std::string& name,
             bool srgb, const std::string& extension, const std::string& interpolation,
             const std::string& alpha, bool unassociate) {
            if (!pixels) throw std::invalid_argument("pixels must not be None");
            ImageTexture t = photon_python::parse_texture(name, srgb, extension, interpolation);
            photon_python::parse_texture_alpha(&t, alpha, unassociate);
            t.pixels = std::move(pixels);
            scene.textures.push_back(std::move(t));
            return scene.textures.size() - 1;
          },
          py::arg("pixels"), py::arg("name"), py::arg("srgb") = true,
          py::arg("extension") = "REPEAT", py::arg("interpolation") = "Linear",
          py::arg("alpha") = "KEEP", py::arg("unassociate") = false,
          "Adds an in-memory image (TexturePixels; `name` names it in warnings); returns its "
          "index. Converted like files, keyed by the pixels' content.")
      .def(
          "add_material",
          [](Scene& scene, const std::string& name, const py::list& closures,
             const py::object& program, float pass_index, const py::object& aovs) {
            std::string warning;
            Material material = photon_python::parse_material(
                name, closures, static_cast<int64_t>(scene.textures.size()), program, &warning,
                aovs);
            if (!warning.empty()) throw py::value_error(warning);
            material.pass_index = pass_index;
            scene.materials.push_back(std::move(material));
            return scene.materials.size() - 1;
          },
          py::arg("name"), py::arg("closures"), py::arg("program") = py::none(),
          py::arg("pass_index") = 0.0f, py::arg("aovs") = py::none(),
          "Adds a material from closure dicts (schema: addon/photon/sync/materials.py); "
          "texture indices refer to add_texture's. `aovs`: its AOV Output nodes, "
          "[{'name', 'type': 'COLOR' | 'VALUE', 'value': input}].")
      .def(
          "add_light",
          [](Scene& scene, const std::string& name, const std::string& type,
             const FloatArray& matrix, const std::vector<float>& color, float power, float radius,
             float spot_size, float spot_blend, float sun_angle, const std::string& shape,
             float size_x, float size_y, uint32_t visibility, const std::string& spectrum,
             float temperature, const std::string& illuminant, bool spot_cosine_falloff,
             float spread, const std::optional<std::string>& ies, float ies_strength,
             const std::string& ies_source, const std::string& ies_edges,
             bool ies_area_by_direction) {
            Light l;
            l.name = name;
            if (type == "POINT")
              l.type = LightType::kPoint;
            else if (type == "SPOT")
              l.type = LightType::kSpot;
            else if (type == "SUN")
              l.type = LightType::kSun;
            else if (type == "AREA")
              l.type = LightType::kArea;
            else
              throw std::invalid_argument("unknown light type " + type);
            l.light_to_world = transform_from(matrix);
            l.color = vec3_from(color, "color");
            l.power = power;
            l.radius = radius;
            l.spot_size = spot_size;
            l.spot_blend = spot_blend;
            l.spot_cosine_falloff = spot_cosine_falloff;
            l.sun_angle = sun_angle;
            l.shape = (shape == "DISK" || shape == "ELLIPSE") ? AreaShape::kEllipse
                                                              : AreaShape::kRectangle;
            l.size_x = size_x;
            l.size_y = (shape == "SQUARE" || shape == "DISK") ? size_x : size_y;
            l.spread = spread;
            l.visibility = visibility & kVisibleAll;
            if (spectrum == "RGB")
              l.spectrum = LightSpectrum::kRgb;
            else if (spectrum == "BLACKBODY")
              l.spectrum = LightSpectrum::kBlackbody;
            else if (spectrum == "ILLUMINANT")
              l.spectrum = LightSpectrum::kIlluminant;
            else
              throw std::invalid_argument("unknown light spectrum " + spectrum);
            l.temperature = temperature;
            if (illuminant == "D65")
              l.illuminant = StandardIlluminant::kD65;
            else if (illuminant == "A")
              l.illuminant = StandardIlluminant::kA;
            else if (illuminant == "F2")
              l.illuminant = StandardIlluminant::kF2;
            else if (illuminant == "F7")
              l.illuminant = StandardIlluminant::kF7;
            else if (illuminant == "F11")
              l.illuminant = StandardIlluminant::kF11;
            else
              throw std::invalid_argument("unknown illuminant " + illuminant);
            l.has_ies = ies.has_value();
            if (ies) l.ies_profile = *ies;
            l.ies_strength = ies_strength;
            l.ies_source = ies_source;
            if (ies_edges == "CLAMP")
              l.ies_edges = IesEdges::kClamp;
            else if (ies_edges == "ZERO")
              l.ies_edges = IesEdges::kZero;
            else if (ies_edges == "HOLD")
              l.ies_edges = IesEdges::kHold;
            else
              throw std::invalid_argument("unknown ies_edges " + ies_edges);
            l.ies_area_by_direction = ies_area_by_direction;
            scene.lights.push_back(std::move(l));
            return scene.lights.size() - 1;
          },
          py::arg("name"), py::arg("type"), py::arg("matrix"), py::arg("color"), py::arg("power"),
          py::arg("radius") = 0.0f, py::arg("spot_size") = 0.785398f, py::arg("spot_blend") = 0.15f,
          py::arg("sun_angle") = 0.0f, py::arg("shape") = "SQUARE", py::arg("size_x") = 1.0f,
          py::arg("size_y") = 1.0f,
          py::arg("visibility") = static_cast<uint32_t>(kVisibleGlossy | kVisibleTransmission),
          py::arg("spectrum") = "RGB", py::arg("temperature") = 6500.0f,
          py::arg("illuminant") = "D65", py::arg("spot_cosine_falloff") = true,
          py::arg("spread") = kPi, py::arg("ies") = py::none(), py::arg("ies_strength") = 1.0f,
          py::arg("ies_source") = "", py::arg("ies_edges") = "HOLD",
          py::arg("ies_area_by_direction") = true,
          "Adds a lamp. `ies`: the IES LM-63 text of an IES Texture node on its Emission "
          "strength (empty: a file that could not be read), scaled by `ies_strength`; "
          "`ies_source` names it in warnings; `ies_edges` ('CLAMP': Cycles 3.x-4.0, 'ZERO': "
          "4.1-5.0, 'HOLD': 5.1+) how the profile's interpolation treats its edges, "
          "`ies_area_by_direction` (Cycles 4.0+) whether an area light reads it per direction "
          "rather than along its axis.")
      .def(
          "add_portal",
          [](Scene& scene, const std::string& name, const FloatArray& matrix,
             const std::string& shape, float size_x, float size_y) {
            const Transform xf = transform_from(matrix);
            Portal p;
            p.name = name;
            p.center = xf.point(Vec3(0.0f));
            p.shape = (shape == "DISK" || shape == "ELLIPSE") ? AreaShape::kEllipse
                                                              : AreaShape::kRectangle;
            const float height = (shape == "SQUARE" || shape == "DISK") ? size_x : size_y;
            p.half_x = xf.vector(Vec3(0.5f * size_x, 0.0f, 0.0f));
            p.half_y = xf.vector(Vec3(0.0f, 0.5f * height, 0.0f));
            p.direction = xf.vector(Vec3(0.0f, 0.0f, -1.0f));
            scene.portals.push_back(std::move(p));
            return scene.portals.size() - 1;
          },
          py::arg("name"), py::arg("matrix"), py::arg("shape") = "SQUARE", py::arg("size_x") = 1.0f,
          py::arg("size_y") = 1.0f,
          "Adds a portal: an area light marked as one (Cycles' Light > Portal), which emits "
          "nothing and guides the world's light and photons through a window. Its light "
          "passes along the light's -Z.")
      .def(
          "set_camera",
          [](Scene& scene, const std::string& projection, const FloatArray& matrix,
             const std::vector<float>& window, float clip_start, float clip_end,
             float aperture_radius, float focus_distance) {
            Camera& c = scene.camera;
            c.projection =
                projection == "ORTHO" ? Projection::kOrthographic : Projection::kPerspective;
            c.set_camera_to_world(transform_from(matrix));
            if (window.size() != 4) throw std::invalid_argument("window: min_x max_x min_y max_y");
            c.window_min_x = window[0];
            c.window_max_x = window[1];
            c.window_min_y = window[2];
            c.window_max_y = window[3];
            c.clip_start = std::max(clip_start, 0.0f);
            c.clip_end = clip_end;
            c.aperture_radius = std::max(aperture_radius, 0.0f);
            c.focus_distance = focus_distance;
          },
          py::arg("projection"), py::arg("matrix"), py::arg("window"), py::arg("clip_start"),
          py::arg("clip_end"), py::arg("aperture_radius") = 0.0f, py::arg("focus_distance") = 10.0f)
      .def(
          "set_world",
          [](Scene& scene, const std::vector<float>& color) {
            const Vec3 c = vec3_from(color, "color");
            const ParamRange r = emitter_range();
            // Non-finite components read as 0 (the add-on reports them).
            auto clamp = [&r](float v) {
              return std::isfinite(v) ? std::clamp(v, r.lo, r.hi) : 0.0f;
            };
            scene.world.color = {clamp(c.x), clamp(c.y), clamp(c.z)};
          },
          py::arg("color"))
      .def(
          "set_world_program",
          [](Scene& scene, const py::object& program, int32_t radiance_reg, bool reads_ray_type) {
            scene.world.program = photon_python::parse_program(program);
            std::string error;
            if (!scene.world.program.empty() &&
                (!validate_program(scene.world.program, &error) || radiance_reg < 0 ||
                 static_cast<size_t>(radiance_reg) + 3 > scene.world.program.registers.size())) {
              scene.world.program = ShaderProgram{};
              scene.world.radiance_reg = -1;
              throw py::value_error("the world's node program is invalid: " +
                                    (error.empty() ? std::string("bad radiance register") : error));
            }
            scene.world.radiance_reg = radiance_reg;
            scene.world.reads_ray_type = reads_ray_type;
          },
          py::arg("program"), py::arg("radiance_reg"), py::arg("reads_ray_type") = false,
          "Sets the world's node program (program_binding.h); the radiance is in three registers "
          "from radiance_reg. set_world's colour stays the fallback.")
      .def(
          "set_world_aovs",
          [](Scene& scene, const py::object& aovs) {
            std::vector<MaterialAov> parsed = photon_python::parse_aovs(aovs, "the world");
            const size_t registers =
                scene.world.program.empty() ? 0 : scene.world.program.registers.size();
            // The world has no UV map: an image read without coordinates keeps its constant.
            for (MaterialAov& aov : parsed) sanitize_aov(&aov, 0, registers);
            scene.world.aovs = std::move(parsed);
          },
          py::arg("aovs"),
          "Sets the world's AOV Output nodes ([{'name', 'type': 'COLOR' | 'VALUE', 'value': "
          "input}], registers of the world program set before), written where camera rays "
          "leave the scene.")
      .def_property_readonly("mesh_count", [](const Scene& s) { return s.meshes.size(); })
      .def_property_readonly("instance_count", [](const Scene& s) { return s.instances.size(); })
      .def_property_readonly("light_count", [](const Scene& s) { return s.lights.size(); })
      .def_property_readonly("portal_count", [](const Scene& s) { return s.portals.size(); })
      .def_property_readonly("material_count", [](const Scene& s) { return s.materials.size(); })
      .def_property_readonly("texture_count", [](const Scene& s) { return s.textures.size(); })
      .def_property_readonly("triangle_count",
                             [](const Scene& s) {
                               size_t n = 0;
                               for (const Mesh& mesh : s.meshes) n += mesh.triangle_count();
                               return n;
                             })
      .def(
          "mesh_corner_normals",
          [](const Scene& s, size_t mesh) {
            if (mesh >= s.meshes.size()) throw std::out_of_range("no such mesh");
            const std::vector<Vec3>& normals = s.meshes[mesh].corner_normals;
            py::array_t<float> out({static_cast<py::ssize_t>(normals.size()), py::ssize_t{3}});
            if (!normals.empty())
              std::memcpy(out.mutable_data(), normals.data(), normals.size() * sizeof(Vec3));
            return out;
          },
          py::arg("mesh"),
          "A mesh's shading normals, three rows per triangle (none without shading normals).");

  // The integrators as the registry lists them.
  py::enum_<IntegratorType> integrator_enum(m, "Integrator");
  for (const IntegratorInfo& info : integrator_registry())
    integrator_enum.value(info.capabilities.name, info.type);

  m.def(
      "integrator_capabilities",
      [](IntegratorType type) {
        const IntegratorCapabilities c = integrator_capabilities(type);
        py::dict d;
        d["name"] = c.name;
        d["bake"] = c.bake;
        d["no_bake_reason"] = c.no_bake_reason;
        d["stop_early"] = c.stop_early;
        d["stop_early_status"] = c.stop_early_status;
        d["prepares"] = c.prepares;
        d["stop_early_effect"] = c.stop_early_effect;
        d["iterative"] = c.iterative;
        d["shares_preparation"] = c.shares_preparation;
        return d;
      },
      py::arg("integrator"),
      "What an Integrator can do: bake (a view-independent solution for lighting bakes; "
      "no_bake_reason otherwise), stop_early (Esc ends its preparation while the status starts "
      "with stop_early_status, and the render goes on as stop_early_effect says), "
      "shares_preparation (RenderSession.set_prepared_state saves and loads its preparation).");
  m.attr("PASS_NAMES") = py::tuple(py::cast(light_pass_names()));

  photon_python::register_data_pass_classes(m);  // before RenderSettings.data_passes
  py::class_<RenderSettings> settings_class(m, "RenderSettings");
  settings_class.def(py::init<>())
      .def_readwrite("full_width", &RenderSettings::full_width)
      .def_readwrite("full_height", &RenderSettings::full_height)
      .def_readwrite("x0", &RenderSettings::x0)
      .def_readwrite("y0", &RenderSettings::y0)
      .def_readwrite("x1", &RenderSettings::x1)
      .def_readwrite("y1", &RenderSettings::y1)
      .def_readwrite("transparent_background", &RenderSettings::transparent_background)
      .def_readwrite("light_passes", &RenderSettings::light_passes)
      .def_readwrite("data_passes", &RenderSettings::data_passes);
  bind_render_params(settings_class);
  // The schema as plain lists and dicts (render_params.h); the add-on generates its
  // properties, panels and make_settings from it.
  m.def("parameter_schema",
        [] { return py::module_::import("json").attr("loads")(render_param_schema_json()); });

  bind_persistent(m);  // before RenderSession, whose blas_cache argument is a BlasCache

  py::class_<RenderSession>(m, "RenderSession")
      .def(py::init([](std::shared_ptr<Scene> scene, const RenderSettings& settings,
                       std::shared_ptr<BlasCache> blas_cache) {
             return std::make_unique<RenderSession>(std::move(scene), settings,
                                                    std::move(blas_cache));
           }),
           py::arg("scene"), py::arg("settings"), py::arg("blas_cache") = nullptr)
      .def("start", &RenderSession::start)
      .def("cancel", &RenderSession::cancel)
      .def("stop_preparation", &RenderSession::stop_preparation)
      .def(
          "set_prepared_state",
          [](RenderSession& s, const std::string& load, const std::string& save,
             bool prepare_only) {
            s.set_prepared_state({load, save, prepare_only});
          },
          py::arg("load") = "", py::arg("save") = "", py::arg("prepare_only") = false,
          "Before start(): load the integrator's preparation (photon maps and caches) from the "
          "file `load` instead of preparing, save it to `save`, and with prepare_only end the "
          "render once prepared (no pixels). A file made for another scene, frame or setting, "
          "or a damaged one, is refused with a warning and the render prepares as usual; "
          "stats.prepared_state says what happened.")
      .def("set_quick_preview", &RenderSession::set_quick_preview, py::arg("enabled"),
           "Before start(): render a quick direct-light preview of the whole region before the "
           "integrator's preparation (take_preview() hands it out).")
      .def(
          "take_preview",
          [](RenderSession& s) -> py::object {
            std::vector<float> rgba;
            if (!s.take_preview(&rgba)) return py::none();
            return to_numpy(std::move(rgba), s.region_height(), s.region_width());
          },
          "The quick preview as rgba[h, w, 4] (y downwards) once it is rendered, else None; "
          "it is handed out once.")
      .def(
          "snapshot",
          [](const RenderSession& s) {
            const JobSnapshot j = s.snapshot();
            py::dict d;
            d["status"] = j.status;
            d["progress"] = j.progress;
            d["preparing"] = j.preparing;
            d["finished"] = j.finished;
            d["cancelled"] = j.cancelled;
            return d;
          },
          "Status, progress (of the current stage), preparing, finished and cancelled, read at "
          "one moment.")
      .def_property_readonly("preparing", &RenderSession::preparing)
      .def("wait", &RenderSession::wait, py::call_guard<py::gil_scoped_release>())
      .def(
          "take_tiles",
          [](RenderSession& s, double timeout) {
            std::vector<Tile> tiles;
            {
              py::gil_scoped_release release;
              tiles = s.take_tiles(timeout);
            }
            py::list out;
            for (Tile& t : tiles) {
              const int w = t.width, h = t.height, x = t.x, y = t.y;
              py::object passes = photon_python::passes_to_dict(std::move(t.passes), h, w);
              out.append(py::make_tuple(x, y, w, h, to_numpy(std::move(t.rgba), h, w), passes));
            }
            return out;
          },
          py::arg("timeout") = 0.1,
          "Finished tiles as (x, y, width, height, rgba[h, w, 4], passes) with y downwards; "
          "passes is {name: [h, w, channels]} holding every other pass of the render by the "
          "name Blender gives it (the light passes of PASS_NAMES when light_passes is set, the "
          "data and Cryptomatte passes of data_passes), or None when there are none.")
      .def_property_readonly("finished", &RenderSession::finished)
      .def_property_readonly("cancelled", &RenderSession::cancelled)
      .def_property_readonly("progress", &RenderSession::progress)
      .def_property_readonly("status", &RenderSession::status)
      .def_property_readonly("warnings", &RenderSession::warnings)
      .def_property_readonly("error", &RenderSession::error,
                             "Why the render failed (status 'Failed'); empty otherwise.")
      .def_property_readonly("stats", &RenderSession::stats)
      .def("image", [](const RenderSession& s) {
        return to_numpy(s.image(), s.region_height(), s.region_width());
      });

  photon_python::register_material_functions(m);
  photon_python::register_program_functions(m);
  photon_python::register_stats_classes(m);
  photon_python::register_sppm_classes(m);

  // Largest lamp power (W, a sun's W/m^2) and world radiance rendered; larger ones are clamped.
  m.attr("MAX_EMISSION") = emitter_range().hi;
  // Abbe numbers of real materials; others are clamped into this range.
  m.attr("ABBE_RANGE") = py::make_tuple(spectral::kMinAbbe, spectral::kMaxAbbe);
  m.attr("VISIBLE_CAMERA") = static_cast<uint32_t>(kVisibleCamera);
  m.attr("VISIBLE_DIFFUSE") = static_cast<uint32_t>(kVisibleDiffuse);
  m.attr("VISIBLE_GLOSSY") = static_cast<uint32_t>(kVisibleGlossy);
  m.attr("VISIBLE_TRANSMISSION") = static_cast<uint32_t>(kVisibleTransmission);
  m.attr("VISIBLE_SHADOW") = static_cast<uint32_t>(kVisibleShadow);

  bind_bake(m);
  bind_progressive(m);
}
