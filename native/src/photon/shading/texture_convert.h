// Converts an image (a file, or float pixels handed over by the add-on) into a tiled,
// MIP-mapped OpenEXR for OpenImageIO's TextureSystem, in a persistent cache keyed by content.
//
// Memory is bounded: the source is streamed in bands of 64 rows (files through an ImageCache of
// bounded size, never read whole), so no full-resolution copy is made; only MIP level 1 (a
// quarter of the pixels) and smaller are held. Float sources stay float (1e6 survives), 8/16-bit
// sources are stored as half. The cancel flag is polled between bands of at most a few MB, so a
// conversion stops within a few tens of milliseconds; make_texture has no progress callback,
// which is why the MIP chain is built here (with make_texture's box filter, see downsample()).
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "photon/scene/material.h"

namespace photon {

// Float RGBA pixels of an image that exists only in memory (Blender's generated images),
// bottom row first as Blender stores them. The add-on fills `data` in place (one copy).
class TexturePixels {
 public:
  TexturePixels(int width, int height, bool is_float);
  int width() const { return width_; }
  int height() const { return height_; }
  bool is_float() const { return is_float_; }  // false: 8-bit values (stored as half)
  float* data() { return data_.get(); }
  // Shared with whoever views the memory (the Python array), so release() is always safe.
  std::shared_ptr<float[]> storage() const;
  // Drops this object's reference once the converted file exists (the content key is kept).
  void release();
  // XXH64 of the pixels (computed once, in parallel chunks), or 0 once released unhashed or
  // when `cancel` became true.
  uint64_t content_hash(const std::atomic<bool>* cancel = nullptr);

 private:
  int width_, height_;
  bool is_float_;
  mutable std::mutex mutex_;
  std::shared_ptr<float[]> data_;
  uint64_t hash_ = 0;
  bool hashed_ = false;
};

struct ConvertedTexture {
  std::string file;                // the cached texture file
  bool srgb_after_lookup = false;  // sRGB files: stored as sRGB, linearised after lookup
  float max_color = 0.0f;          // largest finite colour channel value (after linearising)
  float max_alpha = 0.0f;
  bool reused = false;  // the file was already in the cache
};

struct ConvertRequest {
  std::string path;                       // a file, or empty with `pixels`
  std::shared_ptr<TexturePixels> pixels;  // generated image
  bool srgb = true;
  TextureAlpha alpha = TextureAlpha::kKeep;
};

// Settings part of the cache key; bump when the converted file's contents change meaning.
constexpr const char* kTextureFormatVersion = "photon-tex-v4";

// The content key of a request (file bytes or pixels, plus settings), or 0 with `error`.
uint64_t texture_key(const ConvertRequest& request, const std::atomic<bool>* cancel,
                     std::string* error);

// Converts (or reuses) the texture for `request` whose key is `key` in `cache_dir`. Returns
// false with `error` set (also "cancelled" when `cancel` became true).
bool convert_texture(const ConvertRequest& request, uint64_t key, const std::string& cache_dir,
                     const std::atomic<bool>* cancel, ConvertedTexture* out, std::string* error);

// Least-recently-used eviction: while the cache's .exr files exceed `max_bytes`, deletes the
// oldest (by modification time, refreshed on every reuse) that is not in `keep`. Temporary
// files of conversions that died more than an hour ago go too.
void evict_texture_cache(const std::string& cache_dir, uint64_t max_bytes,
                         const std::vector<std::string>& keep);

// $PHOTON_TEXTURE_CACHE_MB, else 4096 MB.
uint64_t texture_cache_limit_bytes();

}  // namespace photon
