#include "photon/session/image_io.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

namespace photon {

bool write_rgba_image(const std::string& path, const std::vector<float>& rgba, int width,
                      int height, std::string* error) {
  OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::FLOAT);
  OIIO::ImageBuf buf(spec, const_cast<float*>(rgba.data()));
  // Float formats keep scene-linear values; 8-bit formats get sRGB encoding and clamping.
  const bool is_float_format = path.size() > 4 && (path.substr(path.size() - 4) == ".exr" ||
                                                  path.substr(path.size() - 4) == ".hdr");
  bool ok;
  if (is_float_format) {
    ok = buf.write(path);
  } else {
    OIIO::ImageBuf srgb = OIIO::ImageBufAlgo::colorconvert(buf, "linear", "sRGB");
    ok = srgb.write(path, OIIO::TypeDesc::UINT8);
    if (!ok && error) *error = srgb.geterror();
    return ok;
  }
  if (!ok && error) *error = buf.geterror();
  return ok;
}

bool read_rgba_image(const std::string& path, std::vector<float>* rgba, int* width, int* height,
                     std::string* error) {
  OIIO::ImageBuf buf(path);
  if (!buf.read(0, 0, true, OIIO::TypeDesc::FLOAT)) {
    if (error) *error = buf.geterror();
    return false;
  }
  const OIIO::ImageSpec& spec = buf.spec();
  *width = spec.width;
  *height = spec.height;
  rgba->assign(static_cast<size_t>(spec.width) * spec.height * 4, 1.0f);
  const int channels = std::min(spec.nchannels, 4);
  OIIO::ROI roi = buf.roi();
  roi.chbegin = 0;
  roi.chend = channels;
  std::vector<float> tmp(static_cast<size_t>(spec.width) * spec.height * channels);
  if (!buf.get_pixels(roi, OIIO::TypeDesc::FLOAT, tmp.data())) {
    if (error) *error = buf.geterror();
    return false;
  }
  for (size_t i = 0; i < static_cast<size_t>(spec.width) * spec.height; ++i)
    for (int c = 0; c < channels; ++c) (*rgba)[i * 4 + c] = tmp[i * channels + c];
  return true;
}

}  // namespace photon
