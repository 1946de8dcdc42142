// Image textures through OpenImageIO's TextureSystem (tiled, MIP-mapped, cached, thread-safe).
// Each image is converted once to a linear, tiled, MIP-mapped OpenEXR file in a cache folder
// (sRGB images are linearised before filtering, as Blender does), then looked up with the
// node's interpolation and extension.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "photon/material.h"

namespace photon {

class TextureSet {
 public:
  TextureSet();
  // Prepares every texture of `textures`; an image that cannot be read is reported in
  // `warnings` once and its lookups return false (callers use the input's constant).
  TextureSet(const std::vector<ImageTexture>& textures, std::vector<std::string>* warnings);
  ~TextureSet();
  TextureSet(const TextureSet&) = delete;
  TextureSet& operator=(const TextureSet&) = delete;

  size_t size() const;
  bool valid(int index) const;
  // RGBA at Blender UV `uv` (v up). Alpha is 1 for images without an alpha channel; colour is
  // straight (not premultiplied), as Blender's Image Texture node outputs it.
  bool lookup(int index, Vec2 uv, float rgba[4]) const;

  // The folder holding converted textures: $PHOTON_TEXTURE_CACHE, else a folder in the
  // system's temporary directory.
  static std::string cache_directory();

 private:
  struct Entry;
  struct System;
  std::vector<Entry> entries_;  // Entry is defined in textures.cpp
  std::unique_ptr<System> system_;
};

}  // namespace photon
