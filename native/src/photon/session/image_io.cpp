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

}  // namespace photon
