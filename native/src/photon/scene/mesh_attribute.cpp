#include "photon/scene/mesh_attribute.h"

#include <cmath>

namespace photon {

uint64_t attribute_key(const std::string& name) {
  uint64_t h = 14695981039346656037ull;  // FNV-1a offset basis
  for (unsigned char c : name) {
    h ^= c;
    h *= 1099511628211ull;  // FNV prime
  }
  return h;
}

bool add_mesh_attribute(Mesh* mesh, const std::string& name, uint32_t components,
                        const float* values, size_t value_count, std::string* error) {
  if (components < 1 || components > 4) {
    *error = "an attribute has 1 to 4 components, not " + std::to_string(components);
    return false;
  }
  const size_t per_triangle = 3 * static_cast<size_t>(components);
  if (value_count % per_triangle) {
    *error = "attribute '" + name + "': " + std::to_string(value_count) +
             " values are not 3 corners x " + std::to_string(components) +
             " components per triangle";
    return false;
  }
  const size_t given = value_count / per_triangle;
  const size_t kept = mesh->triangle_count();
  const bool remapped = !mesh->source_triangles.empty();
  // Without a remap the triangles are the ones given; with one, every kept triangle's source
  // must be among the values.
  if (remapped ? (mesh->source_triangles.size() != kept ||
                  (kept > 0 && mesh->source_triangles.back() >= given))
               : given != kept) {
    *error = "attribute '" + name + "' has " + std::to_string(given) + " triangles, the mesh " +
             std::to_string(kept);
    return false;
  }
  MeshAttribute attribute;
  attribute.name = name;
  attribute.key = attribute_key(name);
  attribute.components = components;
  attribute.values.resize(kept * per_triangle);
  for (size_t t = 0; t < kept; ++t) {
    const size_t s = remapped ? mesh->source_triangles[t] : t;
    for (size_t i = 0; i < per_triangle; ++i) {
      const float x = values[s * per_triangle + i];
      attribute.values[t * per_triangle + i] = std::isfinite(x) ? x : 0.0f;
    }
  }
  for (MeshAttribute& existing : mesh->attributes)
    if (existing.key == attribute.key && existing.name == name) {
      existing = std::move(attribute);
      return true;
    }
  mesh->attributes.push_back(std::move(attribute));
  return true;
}

const MeshAttribute* find_mesh_attribute(const Mesh& mesh, uint64_t key, const std::string& name) {
  for (const MeshAttribute& a : mesh.attributes)
    if (a.key == key && a.name == name) return &a;
  return nullptr;
}

bool interpolate_attribute(const MeshAttribute& attribute, uint32_t triangle, float u, float v,
                           float out[4]) {
  const size_t n = attribute.components;
  const size_t first = static_cast<size_t>(triangle) * 3 * n;
  if (n < 1 || n > 4 || first + 3 * n > attribute.values.size()) return false;
  const float* c = &attribute.values[first];
  const float w = 1.0f - u - v;
  for (size_t i = 0; i < n; ++i) out[i] = w * c[i] + u * c[n + i] + v * c[2 * n + i];
  return true;
}

}  // namespace photon
