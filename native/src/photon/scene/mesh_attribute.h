// Named mesh attributes: adding them to a mesh (with the triangles clean_mesh dropped), finding
// them by name and interpolating them at a point of a triangle.
#pragma once

#include <cstdint>
#include <string>

#include "photon/scene/scene.h"

namespace photon {

// The key an attribute name is found by (64-bit FNV-1a of its bytes); equal names, equal keys.
uint64_t attribute_key(const std::string& name);

// Adds (or replaces) attribute `name` of `mesh` from `values`: `components` floats per corner,
// three corners per triangle in the order the mesh's triangles were given, before clean_mesh
// dropped any (Mesh::source_triangles maps them). Non-finite values become 0. Returns false
// (and leaves the mesh unchanged) when the counts do not fit: `error` says why.
bool add_mesh_attribute(Mesh* mesh, const std::string& name, uint32_t components,
                        const float* values, size_t value_count, std::string* error);

// The attribute of `mesh` named `name` (its key given), or null.
const MeshAttribute* find_mesh_attribute(const Mesh& mesh, uint64_t key, const std::string& name);

// The attribute's value at barycentrics (u, v) of triangle `triangle` (Embree's convention:
// corner 0 weighs 1 - u - v, corner 1 u, corner 2 v) into out[0 .. components); false when the
// triangle is out of range.
bool interpolate_attribute(const MeshAttribute& attribute, uint32_t triangle, float u, float v,
                           float out[4]);

}  // namespace photon
