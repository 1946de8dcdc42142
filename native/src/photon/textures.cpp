#include "photon/textures.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/texture.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <system_error>

namespace photon {
namespace fs = std::filesystem;

struct TextureSet::Entry {
  OIIO::ustring file;  // the converted texture; empty when the image could not be read
  OIIO::TextureSystem::TextureHandle* handle = nullptr;
  TextureExtension extension = TextureExtension::kRepeat;
  TextureInterpolation interpolation = TextureInterpolation::kLinear;
  int channels = 0;
  bool srgb_after_lookup = false;  // 8-bit sRGB: interpolated as stored, then linearised
};

struct TextureSet::System {
  OIIO::TextureSystem* ts = nullptr;
  System() {
    ts = OIIO::TextureSystem::create(/*shared=*/false);
    ts->attribute("max_memory_MB", 1024.0f);
    ts->attribute("autotile", 64);
  }
  // teardown_imagecache: a private TextureSystem's ImageCache (its open files and cached tiles)
  // is freed only when asked to; without it every render with textures leaked its cache.
  ~System() { OIIO::TextureSystem::destroy(ts, /*teardown_imagecache=*/true); }
};

namespace {

// FNV-1a over the bytes of `text`.
uint64_t hash_text(const std::string& text) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : text) h = (h ^ c) * 1099511628211ull;
  return h;
}

float srgb_to_linear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// Converts `path` to a tiled, MIP-mapped OpenEXR in the cache (once per source file version).
// 8-bit sRGB images keep their sRGB values (`*srgb_after_lookup` is set): Cycles interpolates
// such images as stored and converts after the lookup (NODE_IMAGE_COMPRESS_AS_SRGB), which
// makes texel edges darker than interpolating linear values would. Everything else is stored
// linear. Returns the converted file, or "" with `error` set.
std::string converted_texture(const ImageTexture& tex, bool* srgb_after_lookup,
                              std::string* error) {
  std::error_code ec;
  const fs::path source(tex.path);
  if (tex.path.empty() || !fs::is_regular_file(source, ec)) {
    *error = "file not found";
    return "";
  }
  const auto size = fs::file_size(source, ec);
  const auto mtime = fs::last_write_time(source, ec).time_since_epoch().count();
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  OIIO::ImageBuf src(tex.path, 0, 0, nullptr, &config);
  if (!src.init_spec(tex.path, 0, 0)) {
    *error = src.geterror();
    if (error->empty()) *error = "unreadable image";
    return "";
  }
  *srgb_after_lookup = tex.srgb && src.spec().format == OIIO::TypeDesc::UINT8;
  char name[64];
  std::snprintf(name, sizeof name, "%016llx.exr",
                static_cast<unsigned long long>(hash_text(
                    fs::absolute(source, ec).string() + "|" + std::to_string(size) + "|" +
                    std::to_string(mtime) + "|" + (tex.srgb ? "srgb" : "linear") + "|v2")));
  const fs::path dir(TextureSet::cache_directory());
  fs::create_directories(dir, ec);
  const fs::path out = dir / name;
  if (fs::is_regular_file(out, ec)) return out.string();

  // Straight alpha as stored in PNG/TGA (Blender's Image Texture outputs unpremultiplied
  // colour), then sRGB -> linear on the colour channels only.
  if (!src.read(0, 0, true, OIIO::TypeDesc::FLOAT)) {
    *error = src.geterror();
    if (error->empty()) *error = "unreadable image";
    return "";
  }
  OIIO::ImageBuf linear = src;
  if (tex.srgb && !*srgb_after_lookup && src.nchannels() >= 3) {
    OIIO::ROI roi = src.roi();
    roi.chend = 3;
    if (!OIIO::ImageBufAlgo::colorconvert(linear, src, "sRGB", "linear", false, "", "",
                                           nullptr, roi)) {
      *error = linear.geterror();
      return "";
    }
  }
  OIIO::ImageSpec spec = linear.spec();
  spec.set_format(OIIO::TypeDesc::HALF);
  spec.attribute("maketx:fileformatname", "openexr");
  spec.attribute("maketx:filtername", "box");
  // Write to a temporary name and rename, so concurrent renders never read half a file.
  const fs::path tmp = dir / (std::string(name) + "." + std::to_string(::getpid()) + ".tmp.exr");
  if (!OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxTexture, linear, tmp.string(),
                                        spec)) {
    *error = OIIO::geterror();
    if (error->empty()) *error = "could not write the converted texture";
    fs::remove(tmp, ec);
    return "";
  }
  fs::rename(tmp, out, ec);
  if (ec) {
    *error = ec.message();
    return "";
  }
  return out.string();
}

OIIO::TextureOpt::Wrap wrap_mode(TextureExtension e) {
  switch (e) {
    case TextureExtension::kExtend: return OIIO::TextureOpt::WrapClamp;
    case TextureExtension::kClip: return OIIO::TextureOpt::WrapBlack;
    default: return OIIO::TextureOpt::WrapPeriodic;
  }
}

}  // namespace

std::string TextureSet::cache_directory() {
  if (const char* env = std::getenv("PHOTON_TEXTURE_CACHE"); env && *env) return env;
  std::error_code ec;
  fs::path tmp = fs::temp_directory_path(ec);
  if (ec) tmp = "/tmp";
  return (tmp / ("photon-textures-" + std::to_string(::getuid()))).string();
}

TextureSet::TextureSet() = default;

TextureSet::TextureSet(const std::vector<ImageTexture>& textures,
                       std::vector<std::string>* warnings)
    : entries_(textures.size()) {
  if (textures.empty()) return;
  system_ = std::make_unique<System>();
  for (size_t i = 0; i < textures.size(); ++i) {
    Entry& e = entries_[i];
    e.extension = textures[i].extension;
    e.interpolation = textures[i].interpolation;
    std::string error;
    const std::string file = converted_texture(textures[i], &e.srgb_after_lookup, &error);
    if (file.empty()) {
      if (warnings)
        warnings->push_back("Image '" + textures[i].path + "' cannot be used (" + error +
                            "): its inputs use their fallback colour");
      continue;
    }
    e.file = OIIO::ustring(file);
    e.handle = system_->ts->get_texture_handle(e.file);
    const OIIO::ImageSpec* spec = e.handle ? system_->ts->imagespec(e.handle, nullptr) : nullptr;
    if (!spec) {
      if (warnings)
        warnings->push_back("Image '" + textures[i].path + "' cannot be opened as a texture: " +
                            system_->ts->geterror());
      e.file = OIIO::ustring();
      e.handle = nullptr;
      continue;
    }
    e.channels = spec->nchannels;
  }
}

TextureSet::~TextureSet() = default;

size_t TextureSet::size() const { return entries_.size(); }

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
  if (!ts->texture(e.handle, ts->get_perthread_info(), opt, uv.x, 1.0f - uv.y, 0.0f, 0.0f, 0.0f,
                   0.0f, n, result))
    return false;
  if (n == 1) result[1] = result[2] = result[0];  // grey images
  if (n == 2) {                                    // grey + alpha
    result[3] = result[1];
    result[1] = result[2] = result[0];
  }
  if (e.srgb_after_lookup)
    for (int c = 0; c < 3; ++c) result[c] = srgb_to_linear(result[c]);
  for (int c = 0; c < 4; ++c) rgba[c] = std::isfinite(result[c]) ? result[c] : 0.0f;
  return true;
}

}  // namespace photon
