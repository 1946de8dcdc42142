#include "photon/integrators/prepared_state_fingerprint.h"

#include <OpenImageIO/hash.h>

#include <set>
#include <type_traits>
#include <vector>

#include "photon/integrators/prepared_state_file.h"
#include "photon/integrators/render_params.h"
#include "photon/shading/textures.h"

namespace photon {
namespace {

// Render parameters that cannot change what prepare() computes nor any pixel of the image.
const std::set<std::string>& parameters_left_out() {
  static const std::set<std::string> names = {"threads", "tile_size", "preview_samples"};
  return names;
}

// Collects values field by field (never whole structs, whose padding is undefined); arrays of
// plain values are hashed where they lie and only their hash is collected.
class Fingerprint {
 public:
  template <class T>
  void add(const T& v) {
    static_assert(std::is_arithmetic_v<T> || std::is_enum_v<T>);
    const auto* p = reinterpret_cast<const uint8_t*>(&v);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }
  void add(const Vec2& v) { add(v.x), add(v.y); }
  void add(const Vec3& v) { add(v.x), add(v.y), add(v.z); }
  void add(const Transform& t) {
    for (const auto& row : t.m)
      for (float v : row) add(v);
  }
  void add(const std::string& s) {
    add<uint64_t>(s.size());
    bytes_.insert(bytes_.end(), s.begin(), s.end());
  }
  // Vec2 and Vec3 are packed floats (static_asserts below), so their arrays hash as they lie.
  template <class T>
  void add_array(const std::vector<T>& v) {
    static_assert(std::is_arithmetic_v<T> || std::is_same_v<T, Vec2> || std::is_same_v<T, Vec3>);
    add<uint64_t>(v.size());
    add<uint64_t>(OIIO::xxhash::XXH64(v.data(), v.size() * sizeof(T), 0));
  }
  uint64_t value() const { return OIIO::xxhash::XXH64(bytes_.data(), bytes_.size(), 0); }

 private:
  std::vector<uint8_t> bytes_;
};
static_assert(sizeof(Vec2) == 2 * sizeof(float) && sizeof(Vec3) == 3 * sizeof(float));

void add_program(Fingerprint* f, const ShaderProgram& program) {
  f->add<uint64_t>(program.code.size());
  for (const Instruction& in : program.code) {
    f->add(in.family), f->add(in.kind), f->add(in.mode);
    for (int32_t r : in.in) f->add(r);
    for (int32_t r : in.out) f->add(r);
    for (float p : in.param) f->add(p);
    f->add(in.data), f->add(in.data_size), f->add(in.skip);
  }
  f->add_array(program.registers);
  f->add_array(program.data);
  f->add<uint64_t>(program.attributes.size());
  for (const ProgramAttribute& a : program.attributes) f->add(a.name), f->add(a.key);
}

void add_input(Fingerprint* f, const Input& in) {
  f->add(in.value), f->add(in.texture), f->add(in.channel), f->add(in.reg);
}

void add_material(Fingerprint* f, const Material& m) {
  f->add(m.name);
  f->add<uint64_t>(m.closures.size());
  for (const Closure& c : m.closures) {
    f->add(c.type);
    for (const Input& in : c.params) add_input(f, in);
    f->add(c.sharp), f->add(c.normal.texture), f->add(c.normal.strength);
    f->add(c.normal_reg), f->add(c.clearcoat_normal_reg), f->add(c.abbe);
    if (c.cycles4) f->add(c.cycles4), f->add(c.multiscatter);
    if (c.diffuse_multiscatter) f->add(c.diffuse_multiscatter);
    if (c.beckmann) f->add(c.beckmann);
    f->add<uint64_t>(c.weight.size());
    for (const WeightFactor& w : c.weight) add_input(f, w.fac), f->add(w.complement);
  }
  add_program(f, m.program);
  f->add(m.pass_index), f->add(m.cryptomatte_material);
}

void add_mesh(Fingerprint* f, const Mesh& m) {
  f->add(m.name);
  f->add_array(m.positions);
  f->add_array(m.indices);
  f->add_array(m.corner_normals);
  f->add_array(m.corner_uvs);
  f->add_array(m.material_slots);
  f->add_array(m.source_triangles);
  f->add(m.texspace_location), f->add(m.texspace_size);
  f->add<uint64_t>(m.attributes.size());
  for (const MeshAttribute& a : m.attributes)
    f->add(a.name), f->add(a.key), f->add(a.components), f->add_array(a.values);
}

void add_instance(Fingerprint* f, const Instance& i) {
  f->add(i.name), f->add(i.mesh), f->add(i.object_to_world);
  f->add_array(i.slot_materials);
  f->add(i.visibility), f->add(i.holdout), f->add(i.shadow_catcher);
  f->add(i.color), f->add(i.alpha), f->add(i.random), f->add(i.pass_index);
  f->add(i.cryptomatte_object), f->add(i.cryptomatte_asset);
}

void add_light(Fingerprint* f, const Light& l) {
  f->add(l.name), f->add(l.type), f->add(l.light_to_world), f->add(l.color), f->add(l.power);
  f->add(l.radius), f->add(l.spot_size), f->add(l.spot_blend), f->add(l.sun_angle);
  f->add(l.spot_cosine_falloff);
  f->add(l.shape), f->add(l.size_x), f->add(l.size_y), f->add(l.spread), f->add(l.visibility);
  f->add(l.spectrum), f->add(l.temperature), f->add(l.illuminant);
  if (l.has_ies) {  // only then, so lamps without a profile keep their fingerprints
    f->add(l.ies_profile), f->add(l.ies_strength), f->add(l.ies_edges);
    f->add(l.ies_area_by_direction);
  }
}

void add_camera(Fingerprint* f, const Camera& c) {
  f->add(c.projection), f->add(c.camera_to_world);
  f->add(c.window_min_x), f->add(c.window_max_x), f->add(c.window_min_y), f->add(c.window_max_y);
  f->add(c.clip_start), f->add(c.clip_end), f->add(c.aperture_radius), f->add(c.focus_distance);
}

// A texture by its pixels' content key, not its path: packed and generated images are written
// to a temporary file whose name differs from one Blender process to the next.
void add_texture(Fingerprint* f, const ImageTexture& t, uint64_t content_key) {
  f->add(content_key), f->add(t.srgb), f->add(t.extension), f->add(t.interpolation);
  f->add(t.alpha), f->add(t.unassociate);
}

void add_settings(Fingerprint* f, const RenderSettings& s) {
  f->add(s.full_width), f->add(s.full_height), f->add(s.transparent_background);
  // Exact, whatever the double the schema's accessor returns can hold.
  f->add(s.seed);
  for (const RenderParamGroup& group : render_param_groups())
    for (const RenderParam& p : group.params) {
      if (parameters_left_out().count(p.spec->name)) continue;
      f->add(p.spec->name);
      f->add(p.get(s));
    }
}

}  // namespace

bool prepared_state_fingerprint(const Scene& scene, const RenderSettings& settings,
                                const TextureSet& textures, uint64_t* fingerprint,
                                std::string* why_not) {
  if (scene.world.radiance) {
    if (why_not)
      *why_not =
          "the world's radiance is a function of the program that built the scene, "
          "which a fingerprint cannot cover";
    return false;
  }
  Fingerprint f;
  f.add(kPreparedStateFormat);
  add_settings(&f, settings);
  f.add<uint64_t>(scene.meshes.size());
  for (const Mesh& m : scene.meshes) add_mesh(&f, m);
  f.add<uint64_t>(scene.instances.size());
  for (const Instance& i : scene.instances) add_instance(&f, i);
  f.add<uint64_t>(scene.materials.size());
  for (const Material& m : scene.materials) add_material(&f, m);
  f.add<uint64_t>(scene.textures.size());
  for (size_t i = 0; i < scene.textures.size(); ++i)
    add_texture(&f, scene.textures[i], textures.content_key(static_cast<int>(i)));
  f.add<uint64_t>(scene.lights.size());
  for (const Light& l : scene.lights) add_light(&f, l);
  add_camera(&f, scene.camera);
  f.add(scene.world.color), f.add(scene.world.radiance_reg), f.add(scene.world.reads_ray_type);
  f.add(scene.world.sample_map_width);
  add_program(&f, scene.world.program);
  if (!scene.portals.empty()) {  // only then, so scenes without portals keep their fingerprints
    f.add<uint64_t>(scene.portals.size());
    for (const Portal& p : scene.portals) {
      f.add(p.name), f.add(p.center), f.add(p.half_x), f.add(p.half_y), f.add(p.direction);
      f.add(p.shape);
    }
  }
  *fingerprint = f.value();
  return true;
}

}  // namespace photon
