#include "photon/session/image_io.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace photon {
namespace {

bool ends_with(const std::string& s, const char* suffix) {
  const size_t n = std::strlen(suffix);
  return s.size() >= n && s.compare(s.size() - n, n, suffix) == 0;
}

// `path` with ".<pid>.tmp" before its extension, so OpenImageIO picks the same format.
std::string temporary_name(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  const size_t dot = path.find_last_of('.');
  const bool has_ext = dot != std::string::npos && (slash == std::string::npos || dot > slash);
  const std::string tag = "." + std::to_string(static_cast<long>(getpid())) + ".tmp";
  return has_ext ? path.substr(0, dot) + tag + path.substr(dot) : path + tag;
}

// Whether the file at `path` reads back as a complete width x height image of 4 channels: a
// writer that lost bytes to a full disk can report success (or leave a truncated file).
bool reads_back(const std::string& path, int width, int height, std::string* error) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    *error = "the written file does not read back: " + OIIO::geterror();
    return false;
  }
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width != width || spec.height != height || spec.nchannels != 4) {
    *error = "the written file reads back as a " + std::to_string(spec.width) + "x" +
             std::to_string(spec.height) + " image of " + std::to_string(spec.nchannels) +
             " channels";
    return false;
  }
  std::vector<float> pixels(static_cast<size_t>(width) * height * 4);
  if (!in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, pixels.data())) {
    *error = "the written file does not read back: " + in->geterror();
    return false;
  }
  return true;
}

}  // namespace

bool write_rgba_image(const std::string& path, const std::vector<float>& rgba, int width,
                      int height, std::string* error) {
  std::string message;
  struct stat st;
  if (stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    // Renaming over a directory fails anyway; over a device it would replace the device.
    if (error) *error = path + " exists and is not a regular file";
    return false;
  }
  // Written under a temporary name, read back, then renamed: a failed or short write never
  // leaves a damaged file under the final name (nor replaces a good one).
  const std::string temp = temporary_name(path);
  OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::FLOAT);
  OIIO::ImageBuf buf(spec, const_cast<float*>(rgba.data()));
  // Float formats keep scene-linear values; 8-bit formats get sRGB encoding and clamping.
  const bool is_float_format = ends_with(path, ".exr") || ends_with(path, ".hdr");
  bool ok;
  if (is_float_format) {
    ok = buf.write(temp);
    if (!ok) message = buf.geterror();
  } else {
    OIIO::ImageBuf srgb = OIIO::ImageBufAlgo::colorconvert(buf, "linear", "sRGB");
    ok = srgb.write(temp, OIIO::TypeDesc::UINT8);
    if (!ok) message = srgb.geterror();
  }
  if (ok) ok = reads_back(temp, width, height, &message);
  if (ok && std::rename(temp.c_str(), path.c_str()) != 0) {
    message = "cannot rename " + temp + " to " + path + ": " + std::strerror(errno);
    ok = false;
  }
  if (!ok) {
    std::remove(temp.c_str());
    if (error) *error = message.empty() ? "the image could not be written" : message;
  }
  return ok;
}

}  // namespace photon
