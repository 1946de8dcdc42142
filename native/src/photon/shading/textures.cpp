#include "photon/shading/textures.h"

#include <OpenImageIO/texture.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>
#include <system_error>

#include "photon/shading/texture_convert.h"

namespace photon {
namespace fs = std::filesystem;

struct TextureSet::Entry {
  OIIO::ustring file;  // the converted texture; empty when the image could not be read
  OIIO::TextureSystem::TextureHandle* handle = nullptr;
  TextureExtension extension = TextureExtension::kRepeat;
  TextureInterpolation interpolation = TextureInterpolation::kLinear;
  int channels = 0;
  bool srgb_after_lookup = false;  // sRGB files: interpolated as stored, then linearised
  bool unassociate = false;        // colour divided by alpha after the lookup
  float max_color = 0.0f, max_alpha = 0.0f;
  uint64_t key = 0;  // texture_key of the request
};

struct TextureSet::System {
  using Perthread = OIIO::TextureSystem::Perthread;
  OIIO::TextureSystem* ts = nullptr;
  // Each thread's lookup state, owned here and freed before the set goes.
  tbb::enumerable_thread_specific<Perthread*> infos{nullptr};

  // One private TextureSystem for the process, never torn down. Tearing down a TextureSystem's
  // ImageCache (OpenImageIO 2.4) and creating another corrupted memory: the next render with
  // textures crashed in its BVH build. When the last set goes, the cache drops its tiles and
  // closes its files instead (invalidate_all), so nothing stays in memory between renders.
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  static int& live() {
    static int n = 0;
    return n;
  }
  static OIIO::TextureSystem* shared_system() {
    // A shared_ptr in OpenImageIO 3, a raw pointer in 2.
    static const auto system = [] {
      auto t = OIIO::TextureSystem::create(/*shared=*/false);
      t->attribute("max_memory_MB", 1024.0f);
      t->attribute("autotile", 64);
      return t;
    }();
    return &*system;
  }
  System() {
    std::lock_guard<std::mutex> lock(mutex());
    ts = shared_system();
    ++live();
  }
  Perthread* info() {
    Perthread*& p = infos.local();
    if (!p) p = ts->create_thread_info();
    return p;
  }
  ~System() {
    for (Perthread* p : infos)
      if (p) ts->destroy_thread_info(p);
    std::lock_guard<std::mutex> lock(mutex());
    if (--live() == 0) ts->invalidate_all(/*force=*/true);
  }
};

namespace {

float srgb_to_linear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

OIIO::TextureOpt::Wrap wrap_mode(TextureExtension e) {
  switch (e) {
    case TextureExtension::kExtend:
      return OIIO::TextureOpt::WrapClamp;
    case TextureExtension::kClip:
      return OIIO::TextureOpt::WrapBlack;
    default:
      return OIIO::TextureOpt::WrapPeriodic;
  }
}

}  // namespace

std::string TextureSet::cache_directory() {
  if (const char* env = std::getenv("PHOTON_TEXTURE_CACHE"); env && *env) return env;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return (fs::path(xdg) / "photon" / "textures").string();
  if (const char* home = std::getenv("HOME"); home && *home)
    return (fs::path(home) / ".cache" / "photon" / "textures").string();
  std::error_code ec;
  fs::path tmp = fs::temp_directory_path(ec);
  if (ec) tmp = "/tmp";
  return (tmp / ("photon-textures-" + std::to_string(::getuid()))).string();
}

TextureSet::TextureSet() = default;

TextureSet::TextureSet(const std::vector<ImageTexture>& textures,
                       std::vector<std::string>* warnings, const std::atomic<bool>* cancel)
    : entries_(textures.size()) {
  if (textures.empty()) return;
  const auto t0 = std::chrono::steady_clock::now();
  const size_t n = textures.size();
  auto name = [&](size_t i) {
    return textures[i].pixels ? "Generated image '" + textures[i].path + "'"
                              : "Image '" + textures[i].path + "'";
  };
  std::vector<ConvertRequest> requests(n);
  std::vector<uint64_t> keys(n, 0);
  std::vector<std::string> errors(n);
  for (size_t i = 0; i < n; ++i)
    requests[i] =
        ConvertRequest{textures[i].path, textures[i].pixels, textures[i].srgb, textures[i].alpha};
  // Content keys (hashing reads every byte), then one conversion per distinct key; both in
  // parallel over textures, and each conversion is itself parallel.
  tbb::parallel_for(size_t(0), n,
                    [&](size_t i) { keys[i] = texture_key(requests[i], cancel, &errors[i]); });
  std::map<uint64_t, size_t> first;  // key -> first texture with it
  std::vector<size_t> unique;
  for (size_t i = 0; i < n; ++i)
    if (keys[i] && first.emplace(keys[i], i).second) unique.push_back(i);
  const std::string dir = cache_directory();
  std::vector<ConvertedTexture> converted(n);
  std::vector<char> ok(n, 0);
  tbb::parallel_for(size_t(0), unique.size(), [&](size_t u) {
    const size_t i = unique[u];
    ok[i] = convert_texture(requests[i], keys[i], dir, cancel, &converted[i], &errors[i]);
  });
  cancelled_ = cancel && cancel->load();
  std::vector<std::string> in_use;
  system_ = std::make_unique<System>();
  for (size_t i = 0; i < n && !cancelled_; ++i) {
    Entry& e = entries_[i];
    e.key = keys[i];
    e.extension = textures[i].extension;
    e.interpolation = textures[i].interpolation;
    e.unassociate = textures[i].unassociate && textures[i].alpha == TextureAlpha::kAssociate;
    const size_t j = keys[i] ? first[keys[i]] : i;
    if (!ok[j]) {
      if (warnings)
        warnings->push_back(name(i) + " cannot be used (" +
                            (errors[i].empty() ? errors[j] : errors[i]) +
                            "): its inputs use their fallback colour");
      continue;
    }
    const ConvertedTexture& c = converted[j];
    if (i == j) {
      reused_ += c.reused ? 1 : 0;
      in_use.push_back(c.file);
      // The converted file holds the pixels now; the add-on's copy can go.
      if (textures[i].pixels) textures[i].pixels->release();
    }
    e.srgb_after_lookup = c.srgb_after_lookup;
    e.max_color = c.max_color;
    e.max_alpha = c.max_alpha;
    e.file = OIIO::ustring(c.file);
    e.handle = system_->ts->get_texture_handle(e.file, system_->info());
    const OIIO::ImageSpec* spec =
        e.handle ? system_->ts->imagespec(e.handle, system_->info()) : nullptr;
    if (!spec) {
      if (warnings)
        warnings->push_back(name(i) + " cannot be opened as a texture: " + system_->ts->geterror());
      e.file = OIIO::ustring();
      e.handle = nullptr;
      continue;
    }
    e.channels = spec->nchannels;
  }
  evict_texture_cache(dir, texture_cache_limit_bytes(), in_use);
  seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

float TextureSet::max_color(int index) const {
  return valid(index) ? entries_[index].max_color : 0.0f;
}

uint64_t TextureSet::content_key(int index) const {
  return index >= 0 && static_cast<size_t>(index) < entries_.size() ? entries_[index].key : 0;
}

float TextureSet::max_alpha(int index) const {
  return valid(index) ? entries_[index].max_alpha : 0.0f;
}

TextureSet::~TextureSet() = default;

size_t TextureSet::size() const {
  return entries_.size();
}

bool TextureSet::valid(int index) const {
  return index >= 0 && static_cast<size_t>(index) < entries_.size() && entries_[index].handle;
}

bool TextureSet::lookup(int index, Vec2 uv, float rgba[4]) const {
  if (!valid(index) || !std::isfinite(uv.x) || !std::isfinite(uv.y)) return false;
  const Entry& e = entries_[index];
  OIIO::TextureOpt opt;
  opt.swrap = opt.twrap = wrap_mode(e.extension);
  switch (e.interpolation) {
    case TextureInterpolation::kClosest:
      opt.interpmode = OIIO::TextureOpt::InterpClosest;
      opt.mipmode = OIIO::TextureOpt::MipModeNoMIP;
      break;
    case TextureInterpolation::kCubic:
      opt.interpmode = OIIO::TextureOpt::InterpBicubic;
      break;
    default:
      opt.interpmode = OIIO::TextureOpt::InterpBilinear;
      break;
  }
  opt.firstchannel = 0;
  opt.fill = 1.0f;  // alpha of images without one
  float result[4] = {0.0f, 0.0f, 0.0f, 1.0f};
  const int n = std::min(e.channels, 4);
  OIIO::TextureSystem* ts = system_->ts;
  // Blender's v runs up the image, OpenImageIO's t runs down.
  if (!ts->texture(e.handle, system_->info(), opt, uv.x, 1.0f - uv.y, 0.0f, 0.0f, 0.0f, 0.0f, n,
                   result))
    return false;
  if (n == 1) result[1] = result[2] = result[0];  // grey images
  if (n == 2) {                                   // grey + alpha
    result[3] = result[1];
    result[1] = result[2] = result[0];
  }
  // As Cycles' svm_image_texture: unassociate (alpha neither 0 nor 1), then linearise.
  if (e.unassociate && n == 4 && result[3] != 0.0f && result[3] != 1.0f)
    for (int c = 0; c < 3; ++c) result[c] /= result[3];
  if (e.srgb_after_lookup)
    for (int c = 0; c < 3; ++c) result[c] = srgb_to_linear(result[c]);
  for (int c = 0; c < 4; ++c) rgba[c] = std::isfinite(result[c]) ? result[c] : 0.0f;
  return true;
}

}  // namespace photon
