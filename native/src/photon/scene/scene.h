// Plain-data scene description: what the renderer knows about a scene. No Blender types and no
// Python here, so tests, benchmarks and the CLI build scenes directly.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "photon/base/math.h"
#include "photon/scene/material.h"

namespace photon {

// Ray-visibility bits, mirroring Blender's Object > Visibility > Ray Visibility toggles.
enum Visibility : uint32_t {
  kVisibleCamera = 1u << 0,
  kVisibleDiffuse = 1u << 1,
  kVisibleGlossy = 1u << 2,
  kVisibleTransmission = 1u << 3,
  kVisibleShadow = 1u << 4,
  kVisibleAll = 0x1Fu,
};

// A named per-corner mesh attribute a shader program reads (a UV map, a colour attribute, a
// generic attribute): `components` floats (1 to 4) per corner, three corners per triangle in
// the mesh's triangle order. Point and face domains arrive expanded to corners.
struct MeshAttribute {
  std::string name;
  uint64_t key = 0;         // attribute_key(name), compared before the name
  uint32_t components = 0;  // 1 float, 2 UV, 3 vector, 4 RGBA
  std::vector<float> values;
};

struct Mesh {
  std::string name;
  std::vector<Vec3> positions;
  std::vector<uint32_t> indices;        // three per triangle
  std::vector<Vec3> corner_normals;     // three per triangle, or empty (flat shading)
  std::vector<Vec2> corner_uvs;         // three per triangle, or empty
  std::vector<int32_t> material_slots;  // one per triangle, or empty (slot 0)
  // Index each triangle had as given (before clean_mesh dropped any), or empty when none was
  // dropped: lets a bake address triangles by the caller's numbering (Blender loop triangles).
  std::vector<uint32_t> source_triangles;
  // Blender's texture space (Generated coordinates = (p - (location - size)) / (2 size) in
  // object space): the mesh's bounding box unless the artist set another.
  Vec3 texspace_location{0.0f};
  Vec3 texspace_size{1.0f};
  // Named attributes (shading/attribute_nodes.h reads them; scene/mesh_attribute.h).
  std::vector<MeshAttribute> attributes;

  size_t triangle_count() const { return indices.size() / 3; }
};

struct MeshCleanupReport {
  size_t non_finite_vertices = 0;
  size_t dropped_triangles = 0;  // degenerate, out of range, or touching a non-finite vertex
};

// Drops triangles that cannot be rendered (NaN/inf vertices, zero area, bad indices) and resets
// non-finite vertices and normals, keeping the per-triangle arrays aligned.
MeshCleanupReport clean_mesh(Mesh* mesh);

struct Instance {
  std::string name;
  uint32_t mesh = 0;
  Transform object_to_world;
  std::vector<int32_t> slot_materials;  // material slot -> scene material index
  uint32_t visibility = kVisibleAll;
  // Mattes for compositing, seen only by camera rays (and rays through Transparent BSDFs after
  // them); every other ray meets the object as usual (camera_path.cpp, matte.h).
  bool holdout = false;         // Blender's Object holdout: the pixel becomes transparent
  bool shadow_catcher = false;  // only the shadows cast on it show, as alpha or over the world
  // Object Info node outputs.
  Vec3 color{1.0f};
  float alpha = 1.0f;   // the object colour's alpha (Object Info's Alpha)
  float random = 0.0f;  // in [0, 1]
  float pass_index = 0.0f;
  // Cryptomatte IDs of the object and of its asset (the top of its parent chain), as floats
  // made from the names' hashes (zero: none).
  float cryptomatte_object = 0.0f, cryptomatte_asset = 0.0f;
};

enum class LightType : uint8_t { kPoint, kSpot, kSun, kArea };
enum class AreaShape : uint8_t { kRectangle, kEllipse };

// The spectrum a light emits in spectral mode. Other than kRgb, the spectrum's chromaticity
// replaces the light's colour in both modes (RGB mode renders its Rec.709 colour, so the two
// agree) and the colour's luminance scales it.
enum class LightSpectrum : uint8_t {
  kRgb,         // the colour, uplifted as an illuminant (white is D65)
  kBlackbody,   // Planck's law at `temperature`
  kIlluminant,  // a CIE standard illuminant
};
enum class StandardIlluminant : uint8_t { kD65, kA, kF2, kF7, kF11 };

// Blender light conventions: the light looks down its local -Z axis; `power` is Blender's
// `energy` (W for point, spot and area lights, W/m^2 irradiance for the sun).
// How Cycles' IES lookup treats the table's edges in its cubic interpolation, which changed
// between releases (lights/ies_profile.h): Cycles 3.x-4.0 repeat the last row and wrap around
// the circle always; 4.1-5.0 take zero past an edge the table does not wrap across; 5.1+ repeat
// the edge row there.
enum class IesEdges : uint8_t { kClamp, kZero, kHold };

struct Light {
  std::string name;
  LightType type = LightType::kPoint;
  Transform light_to_world;
  Vec3 color{1.0f, 1.0f, 1.0f};
  float power = 10.0f;
  float radius = 0.0f;       // point and spot: Blender's shadow_soft_size
  float spot_size = 0.785f;  // full cone angle in radians
  float spot_blend = 0.15f;
  // Cycles 3.x multiplies a spot's cone falloff by the cosine to its axis; Cycles 4.0 dropped
  // that factor, so the same spot is brighter off-axis in Blender 4.0+.
  bool spot_cosine_falloff = true;
  float sun_angle = 0.0f;  // angular diameter in radians
  AreaShape shape = AreaShape::kRectangle;
  float size_x = 1.0f, size_y = 1.0f;
  float spread = kPi;  // area: full angle its soft box lets light out over (pi: a bare lamp)
  uint32_t visibility = kVisibleGlossy | kVisibleTransmission;  // lamps hide from camera rays
  LightSpectrum spectrum = LightSpectrum::kRgb;
  float temperature = 6500.0f;  // kelvin, kBlackbody
  StandardIlluminant illuminant = StandardIlluminant::kD65;
  // An IES Texture node on its Emission strength: the IES LM-63 text of its profile (empty: a
  // file that could not be read), times ies_strength (the node's Strength). `ies_source` names
  // it in messages (a file path, a text's name).
  bool has_ies = false;
  std::string ies_profile;
  std::string ies_source;
  float ies_strength = 1.0f;
  IesEdges ies_edges = IesEdges::kHold;
  // Cycles 4.0+ reads an area light's profile along each direction it emits into; 3.x along its
  // axis only.
  bool ies_area_by_direction = true;
};

// An area light marked as a portal (Cycles' Light > Portal, placed in a window): it emits
// nothing and no ray sees it; the world's light is sampled through it and world photons enter
// through it, so an interior lit through its windows converges sooner. `half_x` and `half_y`
// are its half extents (at right angles), `direction` the way light passes through it (the
// light's -Z: into the room).
struct Portal {
  std::string name;
  Vec3 center{0.0f};
  Vec3 half_x{0.5f, 0.0f, 0.0f}, half_y{0.0f, 0.5f, 0.0f};
  Vec3 direction{0.0f, 0.0f, -1.0f};
  AreaShape shape = AreaShape::kRectangle;
};

enum class Projection : uint8_t { kPerspective, kOrthographic };

struct Camera {
  Projection projection = Projection::kPerspective;
  // Rigid (rotation + translation, no scale): camera looks down local -Z, +Y up. Use
  // set_camera_to_world(), which removes scale and shear.
  Transform camera_to_world;
  // Image-plane window in camera space: at distance 1 for perspective, in scene units for
  // orthographic. Blender's sensor fit, lens shift and aspect are already folded in.
  float window_min_x = -0.5f, window_max_x = 0.5f;
  float window_min_y = -0.5f, window_max_y = 0.5f;
  float clip_start = 0.1f, clip_end = 1000.0f;  // along the view axis
  float aperture_radius = 0.0f;                 // thin lens; 0 = pinhole
  float focus_distance = 10.0f;

  // Stores `xf` with its axes orthonormalised (Gram-Schmidt; Blender cameras may carry scale,
  // which Cycles ignores too). A degenerate matrix leaves the identity rotation.
  void set_camera_to_world(const Transform& xf);
};

struct World {
  Vec3 color{0.0f, 0.0f, 0.0f};  // background radiance (colour x strength)
  // A world node tree that is not a constant: its program, evaluated per direction with the
  // background's globals, leaves the radiance in three registers from `radiance_reg`
  // (render/world_shader.h). Empty: the constant colour.
  ShaderProgram program;
  int32_t radiance_reg = -1;
  bool reads_ray_type = false;  // the tree reads Light Path: camera rays see another radiance
  // The tree's AOV Output nodes (registers of `program`), written where camera rays leave the
  // scene (render/world_shader.h).
  std::vector<MaterialAov> aovs;
  // Radiance arriving from a direction (world space, unit, pointing away from the scene), for
  // worlds that vary with direction (an HDRI, a sky); it replaces `color` when set. Called from
  // many threads at once. Importance sampled through a table of sample_map_width x
  // sample_map_width / 2 texels (lights/environment.h).
  std::function<Vec3(const Vec3& direction)> radiance;
  int sample_map_width = 1024;

  static World uniform(const Vec3& color) {
    World w;
    w.color = color;
    return w;
  }
};

struct Scene {
  std::vector<Mesh> meshes;
  std::vector<Instance> instances;
  std::vector<Material> materials;
  std::vector<ImageTexture> textures;  // images read by materials' Input::texture
  std::vector<Light> lights;
  std::vector<Portal> portals;
  Camera camera;
  World world;

  // Material used when a triangle's slot does not map to a valid material.
  static const Material& default_material();
};

}  // namespace photon
