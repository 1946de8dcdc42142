// Image textures through OpenImageIO's TextureSystem (tiled, MIP-mapped, cached, thread-safe).
// Each image is converted once to a linear, tiled, MIP-mapped OpenEXR file in a persistent
// cache folder keyed by content (texture_convert.h; sRGB images are linearised before
// filtering, as Blender does), several at once, then looked up with the node's interpolation
// and extension.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "photon/scene/material.h"

namespace photon {

class TextureSet {
 public:
  TextureSet();
  // Prepares every texture of `textures`; an image that cannot be read is reported in
  // `warnings` once and its lookups return false (callers use the input's constant). When
  // `cancel` becomes true the conversions stop within ~100 ms and cancelled() is true.
  TextureSet(const std::vector<ImageTexture>& textures, std::vector<std::string>* warnings,
             const std::atomic<bool>* cancel = nullptr);
  ~TextureSet();
  TextureSet(const TextureSet&) = delete;
  TextureSet& operator=(const TextureSet&) = delete;

  size_t size() const;
  bool valid(int index) const;
  // RGBA at Blender UV `uv` (v up). Alpha is 1 for images without an alpha channel; colour is
  // straight (not premultiplied), as Blender's Image Texture node outputs it.
  bool lookup(int index, Vec2 uv, float rgba[4]) const;

  // Largest finite colour / alpha value of texture `index` (0 when invalid): inputs with a
  // bounded range warn when their texture exceeds it.
  float max_color(int index) const;
  float max_alpha(int index) const;
  // The content key of texture `index` (its pixels and colour settings, texture_convert.h), also
  // for an image that could not be used; 0 when none could be computed.
  uint64_t content_key(int index) const;
  bool cancelled() const { return cancelled_; }
  size_t reused() const { return reused_; }    // textures found already converted in the cache
  double seconds() const { return seconds_; }  // time spent preparing (hashing, converting)

  // The folder holding converted textures: $PHOTON_TEXTURE_CACHE, else
  // $XDG_CACHE_HOME/photon/textures, else ~/.cache/photon/textures, else the temp directory.
  static std::string cache_directory();

 private:
  struct Entry;
  struct System;
  std::vector<Entry> entries_;  // Entry is defined in textures.cpp
  std::unique_ptr<System> system_;
  bool cancelled_ = false;
  size_t reused_ = 0;
  double seconds_ = 0.0;
};

}  // namespace photon
