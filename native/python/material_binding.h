// Materials and textures between Python and native: parses the closure dicts the add-on builds
// from Blender node trees (addon/photon/sync/materials.py documents the schema) into
// photon::Material, and describes a Material back as the same dicts (tests prove both sides
// agree through _photon.describe_material).
#pragma once

#include <pybind11/pybind11.h>

#include <string>
#include <vector>

#include "photon/scene/material.h"

namespace photon_python {

// Parses `closures` (a list of closure dicts). Unknown keys, types or channels raise
// ValueError; non-finite or out-of-range constants are clamped to Blender's defaults/ranges;
// texture indices outside [0, texture_count) become the param's default constant
// (texture_count < 0: any non-negative index is accepted).
// `program` (None or a program dict, program_binding.h) is compiled into Material::program;
// `warning` (may be null) receives why an invalid program was dropped. `aovs` (None or a list
// of {"name", "type": "COLOR" | "VALUE", "value": input}) are the AOV Output nodes.
photon::Material parse_material(const std::string& name, const pybind11::handle& closures,
                                int64_t texture_count,
                                const pybind11::handle& program = pybind11::none(),
                                std::string* warning = nullptr,
                                const pybind11::handle& aovs = pybind11::none());

// AOV Output nodes: None or [{"name", "type": "COLOR" | "VALUE", "value": input}] (`owner`
// names them in errors); not yet sanitized.
std::vector<photon::MaterialAov> parse_aovs(const pybind11::handle& aovs, const std::string& owner);

// An Image Texture's settings; unknown extension / interpolation names raise ValueError.
photon::ImageTexture parse_texture(const std::string& path, bool srgb, const std::string& extension,
                                   const std::string& interpolation);
// Sets an ImageTexture's alpha handling: alpha "KEEP", "ASSOCIATE" or "IGNORE" (TextureAlpha);
// `unassociate` when the reading node's Alpha output is used.
void parse_texture_alpha(photon::ImageTexture* t, const std::string& alpha, bool unassociate);

// The Material as closure dicts: every param is listed (defaults included).
pybind11::dict describe_material(const photon::Material& material);

// Module-level functions: describe_material(name, closures, texture_count=-1) and
// write_texture(path, rgba[h, w, 4]) (generated images, written by the add-on).
void register_material_functions(pybind11::module_& m);

}  // namespace photon_python
