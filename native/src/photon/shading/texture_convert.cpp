#include "photon/shading/texture_convert.h"

#include <OpenImageIO/hash.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/imageio.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <system_error>

namespace photon {
namespace fs = std::filesystem;

namespace {

constexpr int kTile = 64;            // tile size of the converted files (make_texture's default)
constexpr int kChunkColumns = 1024;  // columns processed between two cancel polls
constexpr size_t kHashChunk = size_t(64) << 20;

bool cancelled(const std::atomic<bool>* cancel) {
  return cancel && cancel->load();
}

uint64_t combine(const std::vector<uint64_t>& parts, uint64_t seed) {
  return OIIO::xxhash::XXH64(parts.data(), parts.size() * sizeof(uint64_t), seed);
}

// Where the pixels of a request come from, one band of rows (top row first) at a time.
class BandSource {
 public:
  virtual ~BandSource() = default;
  int width = 0, height = 0, channels = 0;
  std::vector<std::string> channel_names;
  OIIO::TypeDesc format = OIIO::TypeDesc::FLOAT;
  // Colour not premultiplied by alpha (OpenImageIO's oiio:UnassociatedAlpha: PNG, TGA, most
  // TIFFs; Blender's byte buffers). Otherwise (OpenEXR, Blender's float buffers) it is.
  bool unassociated = false;
  // Rows [y0, y1) as float, `channels` per pixel, into `dst` (row stride width * channels).
  virtual bool fetch(int y0, int y1, float* dst, std::string* error) const = 0;
};

class PixelSource : public BandSource {
 public:
  explicit PixelSource(std::shared_ptr<float[]> data, int w, int h, bool is_float)
      : data_(std::move(data)) {
    width = w;
    height = h;
    channels = 4;
    channel_names = {"R", "G", "B", "A"};
    format = is_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8;
    unassociated = !is_float;
  }
  bool fetch(int y0, int y1, float* dst, std::string*) const override {
    const size_t row = static_cast<size_t>(width) * 4;
    for (int y = y0; y < y1; ++y)  // Blender stores the bottom row first
      std::memcpy(dst + (y - y0) * row, data_.get() + (height - 1 - y) * row, row * sizeof(float));
    return true;
  }

 private:
  std::shared_ptr<float[]> data_;
};

// The ImageCache every conversion reads its source through: bounded in size, so tiles come
// and go and no whole image is ever in memory. One for the process, never destroyed: OIIO 2.4
// keeps per-thread state of each cache in its worker threads, and creating and destroying a
// private cache per file crashed inside OIIO (ImageCacheImpl::verify_file) once several had
// come and gone. OIIO 3 hands caches out as shared_ptr, OIIO 2 as a raw pointer.
using CacheHandle = decltype(OIIO::ImageCache::create(false));
const CacheHandle& conversion_cache() {
  static const CacheHandle cache = [] {
    CacheHandle c = OIIO::ImageCache::create(/*shared=*/false);
    c->attribute("max_memory_MB", 256.0f);
    c->attribute("autotile", kTile);
    c->attribute("autoscanline", 1);
    c->attribute("unassociatedalpha", 1);  // straight alpha, as Blender outputs it
    return c;
  }();
  return cache;
}

// A source file read in bands through conversion_cache(), by one FileSource at a time per path.
// Two conversions of one file at once (an image used as colour and as data, or two renders)
// in OIIO 2.4's cache read zero pixels now and then, and one closing the file under the other
// asserted inside OIIO; so each path has a lock a FileSource holds from open to close.
class FileSource : public BandSource {
 public:
  FileSource() : cache_(conversion_cache()) {}
  ~FileSource() override {
    buf_.reset();
    if (path_.empty()) return;
    // Close the file and drop its tiles (a later render may convert a changed file of the
    // same name).
    cache_->invalidate(OIIO::ustring(path_), /*force=*/true);
    lock_.unlock();
    std::lock_guard<std::mutex> guard(paths_mutex());
    auto it = paths().find(path_);
    if (--it->second.users == 0) paths().erase(it);
  }
  bool open(const std::string& path, std::string* error) {
    {
      std::lock_guard<std::mutex> guard(paths_mutex());
      PathLock& entry = paths()[path];  // std::map: the entry stays put while others come
      ++entry.users;
      lock_ = std::unique_lock<std::mutex>(entry.mutex, std::defer_lock);
    }
    lock_.lock();
    path_ = path;
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);  // straight alpha, as Blender outputs it
    buf_ = std::make_unique<OIIO::ImageBuf>(path, 0, 0, cache_, &config);
    if (!buf_->init_spec(path, 0, 0)) {
      *error = buf_->geterror();
      if (error->empty()) *error = "unreadable image";
      return false;
    }
    const OIIO::ImageSpec& spec = buf_->spec();
    width = spec.width;
    height = spec.height;
    channels = std::clamp(spec.nchannels, 1, 4);
    format = spec.format;
    unassociated = spec.get_int_attribute("oiio:UnassociatedAlpha", 0) != 0;
    for (int c = 0; c < channels; ++c)
      channel_names.push_back(c < static_cast<int>(spec.channelnames.size())
                                  ? spec.channelnames[c]
                                  : std::string(1, "RGBA"[c]));
    if (width <= 0 || height <= 0) {
      *error = "empty image";
      return false;
    }
    return true;
  }
  bool fetch(int y0, int y1, float* dst, std::string* error) const override {
    const OIIO::ImageSpec& spec = buf_->spec();
    const OIIO::ROI roi(spec.x, spec.x + width, spec.y + y0, spec.y + y1, spec.z, spec.z + 1, 0,
                        channels);
    if (!buf_->get_pixels(roi, OIIO::TypeDesc::FLOAT, dst)) {
      *error = buf_->geterror();
      if (error->empty()) *error = "unreadable pixels";
      return false;
    }
    return true;
  }

 private:
  struct PathLock {
    std::mutex mutex;
    int users = 0;  // FileSources holding or waiting for `mutex`
  };
  static std::map<std::string, PathLock>& paths() {
    static std::map<std::string, PathLock> p;
    return p;
  }
  static std::mutex& paths_mutex() {
    static std::mutex m;
    return m;
  }

  CacheHandle cache_ = nullptr;
  std::string path_;
  std::unique_lock<std::mutex> lock_;
  std::unique_ptr<OIIO::ImageBuf> buf_;
};

// Rows of one MIP level's source, addressed by absolute row index.
using RowFn = std::function<const float*(int)>;

// One destination row of the next MIP level, with make_texture's "box" filter: exact 2x2
// averages when both sizes halve exactly (its resize_block_2pass: two halvings, in that order,
// so results match it), otherwise bilinear interpolation at the destination pixel centre in
// normalized coordinates, clamped at the edges (its resize_block_ / interppixel_NDC_clamped).
void downsample_row(const RowFn& src_row, int sw, int sh, int dw, int dh, int nch, int y,
                    float* dst) {
  if (sw == 2 * dw && sh == 2 * dh) {
    const float* a = src_row(2 * y);
    const float* b = src_row(2 * y + 1);
    for (int x = 0; x < dw; ++x)
      for (int c = 0; c < nch; ++c) {
        const int i = 2 * x * nch + c;
        const float s0 = 0.5f * (a[i] + a[i + nch]);
        const float s1 = 0.5f * (b[i] + b[i + nch]);
        dst[x * nch + c] = 0.5f * (s0 + s1);
      }
    return;
  }
  const float t = (y + 0.5f) * (1.0f / dh) * sh - 0.5f;
  const float fy0 = std::floor(t);
  const float yfrac = t - fy0;
  const int r0 = std::clamp(static_cast<int>(fy0), 0, sh - 1);
  const int r1 = std::clamp(static_cast<int>(fy0) + 1, 0, sh - 1);
  const float* a = src_row(r0);
  const float* b = src_row(r1);
  for (int x = 0; x < dw; ++x) {
    const float s = (x + 0.5f) * (1.0f / dw) * sw - 0.5f;
    const float fx0 = std::floor(s);
    const float xfrac = s - fx0;
    const int c0 = std::clamp(static_cast<int>(fx0), 0, sw - 1);
    const int c1 = std::clamp(static_cast<int>(fx0) + 1, 0, sw - 1);
    for (int c = 0; c < nch; ++c) {
      const float top = (1.0f - xfrac) * a[c0 * nch + c] + xfrac * a[c1 * nch + c];
      const float bottom = (1.0f - xfrac) * b[c0 * nch + c] + xfrac * b[c1 * nch + c];
      dst[x * nch + c] = (1.0f - yfrac) * top + yfrac * bottom;
    }
  }
}

// The highest source row that destination row `y` reads.
int last_row_needed(int sh, int dh, int y) {
  if (sh == 2 * dh) return 2 * y + 1;
  const float t = (y + 0.5f) * (1.0f / dh) * sh - 0.5f;
  return std::clamp(static_cast<int>(std::floor(t)) + 1, 0, sh - 1);
}

// Writes rows [y0, y1) of the open level from `rows` (row stride width * nch floats) in chunks
// of kChunkColumns columns, polling `cancel` between chunks.
bool write_band(OIIO::ImageOutput* out, int width, int nch, int y0, int y1, const float* rows,
                const std::atomic<bool>* cancel, std::string* error) {
  const OIIO::stride_t xstride = nch * sizeof(float);
  const OIIO::stride_t ystride = static_cast<OIIO::stride_t>(width) * xstride;
  for (int x0 = 0; x0 < width; x0 += kChunkColumns) {
    if (cancelled(cancel)) {
      *error = "cancelled";
      return false;
    }
    const int x1 = std::min(width, x0 + kChunkColumns);
    if (!out->write_tiles(x0, x1, y0, y1, 0, 1, OIIO::TypeDesc::FLOAT, rows + x0 * nch, xstride,
                          ystride)) {
      *error = out->geterror();
      if (error->empty()) *error = "cannot write the converted texture";
      return false;
    }
  }
  return true;
}

struct MaxPair {
  float color = 0.0f, alpha = 0.0f;
};

// Largest finite colour and alpha values of `n` pixels.
MaxPair band_max(const float* p, size_t n, int nch) {
  const int colors = nch >= 3 ? 3 : 1;
  const int alpha = nch == 4 ? 3 : (nch == 2 ? 1 : -1);
  return tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, n, 4096), MaxPair{},
      [&](const tbb::blocked_range<size_t>& r, MaxPair m) {
        for (size_t i = r.begin(); i < r.end(); ++i) {
          const float* px = p + i * nch;
          for (int c = 0; c < colors; ++c)
            if (std::isfinite(px[c])) m.color = std::max(m.color, px[c]);
          if (alpha >= 0 && std::isfinite(px[alpha])) m.alpha = std::max(m.alpha, px[alpha]);
        }
        return m;
      },
      [](MaxPair a, MaxPair b) {
        return MaxPair{std::max(a.color, b.color), std::max(a.alpha, b.alpha)};
      });
}

// Converts `src` into a tiled MIP-mapped OpenEXR at `tmp`.
// Cycles' alpha handling at load (OIIOImageLoader, BlenderImageLoader): the colour of an
// unassociated source becomes the colour times alpha, for 8-bit sources in integers
// (c a / 255, truncated) as Cycles stores them; ignored alpha becomes 1. Rows of RGBA floats
// (8-bit values as v / 255), in place.
void apply_alpha(float* rows, size_t pixels, TextureAlpha alpha, bool byte_source) {
  for (size_t i = 0; i < pixels; ++i) {
    float* px = rows + 4 * i;
    if (alpha == TextureAlpha::kIgnore) {
      px[3] = 1.0f;
    } else if (byte_source) {
      const int a = static_cast<int>(std::lround(std::clamp(px[3], 0.0f, 1.0f) * 255.0f));
      for (int c = 0; c < 3; ++c) {
        const int v = static_cast<int>(std::lround(std::clamp(px[c], 0.0f, 1.0f) * 255.0f));
        px[c] = static_cast<float>(v * a / 255) / 255.0f;
      }
    } else {
      for (int c = 0; c < 3; ++c) px[c] *= px[3];
    }
  }
}

bool write_mip_chain(const BandSource& src, bool linearize, TextureAlpha alpha, bool byte_source,
                     OIIO::TypeDesc out_format, const std::string& tmp,
                     const std::atomic<bool>* cancel, ConvertedTexture* result,
                     std::string* error) {
  const int w = src.width, h = src.height, nch = src.channels;
  auto out = OIIO::ImageOutput::create("openexr");
  if (!out) {
    *error = "OpenEXR output is not available";
    return false;
  }
  OIIO::ImageSpec spec(w, h, nch, out_format);
  spec.channelnames = src.channel_names;
  spec.tile_width = spec.tile_height = kTile;
  // RLE: ten times faster than zip here (zip made conversion the slowest stage) and it still
  // shrinks the flat regions generated images are made of.
  spec.attribute("compression", "rle");
  // "Plain Texture" makes OpenImageIO's EXR writer store MIP levels (as make_texture does).
  spec.attribute("textureformat", "Plain Texture");
  if (!out->open(tmp, spec, OIIO::ImageOutput::Create)) {
    *error = out->geterror();
    return false;
  }

  // Level 0, streamed in bands of kTile rows; level 1 is built from the bands as they pass
  // (one row of the previous band is kept: bilinear rows may straddle two bands).
  const int w1 = std::max(1, w / 2), h1 = std::max(1, h / 2);
  const bool mip = w > 1 || h > 1;
  // Not zero-filled: every value is written before it is read, and touching a large buffer
  // all at once here would take long (page faults) without a cancel poll.
  std::unique_ptr<float[]> level1(mip ? new float[static_cast<size_t>(w1) * h1 * nch] : nullptr);
  const size_t row_floats = static_cast<size_t>(w) * nch;
  std::vector<float> band((kTile + 1) * row_floats);  // row 0: last row of the previous band
  int band_y0 = 0;
  int next_row1 = 0;
  const RowFn band_row = [&](int r) {
    return band.data() + static_cast<size_t>(r - band_y0 + 1) * row_floats;
  };
  OIIO::ImageSpec band_spec(w, kTile, nch, OIIO::TypeDesc::FLOAT);
  MaxPair maxima;
  for (int y0 = 0; y0 < h; y0 += kTile) {
    const int y1 = std::min(h, y0 + kTile);
    if (y0 > 0) std::memcpy(band.data(), band.data() + kTile * row_floats, row_floats * 4);
    band_y0 = y0;
    float* rows = band.data() + row_floats;
    if (cancelled(cancel)) {
      *error = "cancelled";
      return false;
    }
    if (!src.fetch(y0, y1, rows, error)) return false;
    if (nch == 4 &&
        (alpha == TextureAlpha::kIgnore || (alpha == TextureAlpha::kAssociate && src.unassociated)))
      apply_alpha(rows, static_cast<size_t>(y1 - y0) * w, alpha, byte_source);
    if (linearize) {
      // sRGB -> linear on the colour channels only (alpha is not colour), in place.
      OIIO::ImageBuf wrapped(band_spec, rows);
      for (int x0 = 0; x0 < w; x0 += kChunkColumns) {
        if (cancelled(cancel)) {
          *error = "cancelled";
          return false;
        }
        const OIIO::ROI roi(x0, std::min(w, x0 + kChunkColumns), 0, y1 - y0, 0, 1, 0, 3);
        if (!OIIO::ImageBufAlgo::colorconvert(wrapped, wrapped, "sRGB", "linear", false, "", "",
                                              nullptr, roi)) {
          *error = wrapped.geterror();
          return false;
        }
      }
    }
    const MaxPair m = band_max(rows, static_cast<size_t>(y1 - y0) * w, nch);
    maxima.color = std::max(maxima.color, m.color);
    maxima.alpha = std::max(maxima.alpha, m.alpha);
    if (!write_band(out.get(), w, nch, y0, y1, rows, cancel, error)) return false;
    if (mip) {
      int end = next_row1;
      while (end < h1 && last_row_needed(h, h1, end) < y1) ++end;
      tbb::parallel_for(next_row1, end, [&](int y) {
        downsample_row(band_row, w, h, w1, h1, nch, y, &level1[static_cast<size_t>(y) * w1 * nch]);
      });
      next_row1 = end;
    }
  }
  result->max_color = maxima.color;
  result->max_alpha = maxima.alpha;

  // Levels 1.. from memory; each is a quarter of the one before.
  int lw = w1, lh = h1;
  std::unique_ptr<float[]> level = std::move(level1);
  while (mip) {
    OIIO::ImageSpec level_spec = spec;
    level_spec.width = level_spec.full_width = lw;
    level_spec.height = level_spec.full_height = lh;
    if (!out->open(tmp, level_spec, OIIO::ImageOutput::AppendMIPLevel)) {
      *error = out->geterror();
      return false;
    }
    for (int y0 = 0; y0 < lh; y0 += kTile)
      if (!write_band(out.get(), lw, nch, y0, std::min(lh, y0 + kTile),
                      level.get() + static_cast<size_t>(y0) * lw * nch, cancel, error))
        return false;
    if (lw == 1 && lh == 1) break;
    const int nw = std::max(1, lw / 2), nh = std::max(1, lh / 2);
    std::unique_ptr<float[]> next(new float[static_cast<size_t>(nw) * nh * nch]);
    const RowFn level_row = [&](int r) { return level.get() + static_cast<size_t>(r) * lw * nch; };
    for (int y0 = 0; y0 < nh; y0 += kTile) {
      if (cancelled(cancel)) {
        *error = "cancelled";
        return false;
      }
      tbb::parallel_for(y0, std::min(nh, y0 + kTile), [&](int y) {
        downsample_row(level_row, lw, lh, nw, nh, nch, y, &next[static_cast<size_t>(y) * nw * nch]);
      });
    }
    level = std::move(next);
    lw = nw;
    lh = nh;
  }
  if (!out->close()) {
    *error = out->geterror();
    return false;
  }
  return true;
}

// The stats of a converted file live in a small text file beside it ("<key>.exr.stats"): they
// are known only once the pixels are written, after the EXR header.
std::string stats_path(const fs::path& file) {
  return file.string() + ".stats";
}

bool read_stats(const fs::path& file, ConvertedTexture* result) {
  std::ifstream in(stats_path(file));
  int after = 0;
  if (!(in >> result->max_color >> result->max_alpha >> after)) return false;
  result->srgb_after_lookup = after != 0;
  return true;
}

bool write_stats(const fs::path& file, const ConvertedTexture& result) {
  std::ofstream out(stats_path(file));
  char text[96];
  std::snprintf(text, sizeof text, "%.9g %.9g %d\n", result.max_color, result.max_alpha,
                result.srgb_after_lookup ? 1 : 0);
  out << text;
  return static_cast<bool>(out);
}

}  // namespace

TexturePixels::TexturePixels(int width, int height, bool is_float)
    : width_(std::max(width, 1)), height_(std::max(height, 1)), is_float_(is_float) {
  // Not zero-filled: the add-on overwrites every value (foreach_get), and zero-filling
  // gigabytes first costs seconds of page faults.
  data_ = std::shared_ptr<float[]>(new float[static_cast<size_t>(width_) * height_ * 4]);
}

std::shared_ptr<float[]> TexturePixels::storage() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return data_;
}

void TexturePixels::release() {
  std::lock_guard<std::mutex> lock(mutex_);
  data_.reset();
}

uint64_t TexturePixels::content_hash(const std::atomic<bool>* cancel) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (hashed_ || !data_) return hash_;
  const size_t bytes = static_cast<size_t>(width_) * height_ * 4 * sizeof(float);
  const size_t chunks = (bytes + kHashChunk - 1) / kHashChunk;
  std::vector<uint64_t> parts(chunks);
  const char* base = reinterpret_cast<const char*>(data_.get());
  tbb::parallel_for(size_t(0), chunks, [&](size_t i) {
    if (cancelled(cancel)) return;  // one 64 MB chunk takes ~10 ms
    const size_t begin = i * kHashChunk;
    parts[i] = OIIO::xxhash::XXH64(base + begin, std::min(kHashChunk, bytes - begin), i);
  });
  if (cancelled(cancel)) return 0;
  hash_ = combine(parts, bytes);
  hashed_ = true;
  return hash_;
}

uint64_t texture_key(const ConvertRequest& request, const std::atomic<bool>* cancel,
                     std::string* error) {
  uint64_t content = 0;
  std::string what;
  if (request.pixels) {
    content = request.pixels->content_hash(cancel);
    what = "pixels|" + std::to_string(request.pixels->width()) + "x" +
           std::to_string(request.pixels->height()) + (request.pixels->is_float() ? "f" : "b");
  } else {
    std::ifstream in(request.path, std::ios::binary);
    std::error_code ec;
    if (request.path.empty() || !fs::is_regular_file(request.path, ec) || !in) {
      *error = "file not found";
      return 0;
    }
    // The file's bytes decide: a touched or moved file still hits, an edited one misses.
    std::vector<uint64_t> parts;
    std::vector<char> chunk(size_t(16) << 20);
    uint64_t size = 0;
    while (in) {
      if (cancelled(cancel)) {
        *error = "cancelled";
        return 0;
      }
      in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
      const size_t n = static_cast<size_t>(in.gcount());
      if (n == 0) break;
      parts.push_back(OIIO::xxhash::XXH64(chunk.data(), n, parts.size()));
      size += n;
    }
    content = combine(parts, size);
    what = "file|" + std::to_string(size);
  }
  if (cancelled(cancel)) {
    *error = "cancelled";
    return 0;
  }
  const std::string settings = std::string(kTextureFormatVersion) + "|" + what + "|" +
                               (request.srgb ? "srgb" : "linear") +
                               (request.alpha == TextureAlpha::kAssociate ? "|premultiplied"
                                : request.alpha == TextureAlpha::kIgnore  ? "|ignore-alpha"
                                                                          : "");
  const uint64_t key = OIIO::xxhash::XXH64(settings.data(), settings.size(), content);
  return key ? key : 1;
}

namespace {

bool convert_texture_here(const ConvertRequest& request, uint64_t key, const std::string& cache_dir,
                          const std::atomic<bool>* cancel, ConvertedTexture* out,
                          std::string* error) {
  std::error_code ec;
  const fs::path dir(cache_dir);
  fs::create_directories(dir, ec);
  char name[32];
  std::snprintf(name, sizeof name, "%016llx.exr", static_cast<unsigned long long>(key));
  const fs::path file = dir / name;
  out->file = file.string();
  if (fs::is_regular_file(file, ec) && read_stats(file, out)) {
    fs::last_write_time(file, fs::file_time_type::clock::now(), ec);  // recently used
    out->reused = true;
    return true;
  }

  std::unique_ptr<BandSource> src;
  bool linearize = false;
  bool byte_source = false;
  OIIO::TypeDesc out_format = OIIO::TypeDesc::HALF;
  if (request.pixels) {
    std::shared_ptr<float[]> data = request.pixels->storage();
    if (!data) {
      *error = "its pixels were released and the converted file is gone";
      return false;
    }
    src = std::make_unique<PixelSource>(std::move(data), request.pixels->width(),
                                        request.pixels->height(), request.pixels->is_float());
    linearize = request.srgb;
    byte_source = !request.pixels->is_float();
    out_format = request.pixels->is_float() ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::HALF;
  } else {
    auto file_src = std::make_unique<FileSource>();
    if (!file_src->open(request.path, error)) return false;
    const OIIO::TypeDesc::BASETYPE base = OIIO::TypeDesc::BASETYPE(file_src->format.basetype);
    // sRGB images keep their sRGB values, whatever their depth: Cycles interpolates such images
    // as stored and converts after the lookup (compress_as_srgb, NODE_IMAGE_COMPRESS_AS_SRGB).
    out->srgb_after_lookup = request.srgb;
    byte_source = base == OIIO::TypeDesc::UINT8;
    // Integer and half sources fit half exactly enough; float sources keep float range.
    const bool small = base == OIIO::TypeDesc::UINT8 || base == OIIO::TypeDesc::INT8 ||
                       base == OIIO::TypeDesc::UINT16 || base == OIIO::TypeDesc::INT16 ||
                       base == OIIO::TypeDesc::HALF;
    out_format = small ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT;
    src = std::move(file_src);
  }

  // Write to a unique temporary name and rename, so concurrent renders never read half a file.
  static std::atomic<uint64_t> counter{0};
  const fs::path tmp = dir / (std::string(name) + "." + std::to_string(::getpid()) + "." +
                              std::to_string(counter++) + ".tmp.exr");
  if (!write_mip_chain(*src, linearize, request.alpha, byte_source, out_format, tmp.string(),
                       cancel, out, error)) {
    fs::remove(tmp, ec);
    return false;
  }
  if (out->srgb_after_lookup && out->max_color > 0.04045f)  // the largest linear value
    out->max_color = std::pow((out->max_color + 0.055f) / 1.055f, 2.4f);
  else if (out->srgb_after_lookup)
    out->max_color /= 12.92f;
  // Stats first: a file without them counts as missing and would be converted again.
  if (!write_stats(file, *out)) {
    *error = "cannot write " + stats_path(file);
    fs::remove(tmp, ec);
    return false;
  }
  fs::rename(tmp, file, ec);
  if (ec) {
    *error = ec.message();
    fs::remove(tmp, ec);
    return false;
  }
  return true;
}

}  // namespace

bool convert_texture(const ConvertRequest& request, uint64_t key, const std::string& cache_dir,
                     const std::atomic<bool>* cancel, ConvertedTexture* out, std::string* error) {
  // Isolated: while this thread waits in the conversion's own parallel loops it must not pick
  // up another texture's conversion, which could wait for the source-file lock this one holds.
  return tbb::this_task_arena::isolate(
      [&] { return convert_texture_here(request, key, cache_dir, cancel, out, error); });
}

uint64_t texture_cache_limit_bytes() {
  if (const char* env = std::getenv("PHOTON_TEXTURE_CACHE_MB"); env && *env) {
    char* end = nullptr;
    const double mb = std::strtod(env, &end);
    if (end != env && std::isfinite(mb) && mb >= 0.0) return static_cast<uint64_t>(mb * 1048576.0);
  }
  return uint64_t(4096) << 20;
}

void evict_texture_cache(const std::string& cache_dir, uint64_t max_bytes,
                         const std::vector<std::string>& keep) {
  std::error_code ec;
  struct Item {
    fs::path path;
    fs::file_time_type time;
    uint64_t size;
  };
  std::vector<Item> items;
  uint64_t total = 0;
  const auto now = fs::file_time_type::clock::now();
  for (fs::directory_iterator it(cache_dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (!it->is_regular_file(ec)) continue;
    const fs::path p = it->path();
    const std::string name = p.filename().string();
    const auto time = fs::last_write_time(p, ec);
    if (name.size() > 8 && name.compare(name.size() - 8, 8, ".tmp.exr") == 0) {
      if (now - time > std::chrono::hours(1)) fs::remove(p, ec);
      continue;
    }
    if (p.extension() != ".exr") continue;
    const uint64_t size = it->file_size(ec);
    total += size;
    if (std::find(keep.begin(), keep.end(), p.string()) == keep.end())
      items.push_back({p, time, size});
  }
  std::sort(items.begin(), items.end(),
            [](const Item& a, const Item& b) { return a.time < b.time; });
  for (const Item& item : items) {
    if (total <= max_bytes) break;
    if (fs::remove(item.path, ec)) total -= item.size;
    fs::remove(stats_path(item.path), ec);
  }
}

}  // namespace photon
