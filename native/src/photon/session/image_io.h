// Writing RGBA float images through OpenImageIO (EXR stays linear float).
#pragma once

#include <string>
#include <vector>

namespace photon {

// Writes width x height RGBA pixels (rows top first) to `path` in the format its extension
// names: under a temporary name beside it, read back whole, then renamed, so a failed or short
// write (a full disk) never leaves a damaged file under `path`. False with `error` set when
// anything fails, `path` untouched; a `path` that exists and is not a regular file (a folder,
// a device) is refused.
bool write_rgba_image(const std::string& path, const std::vector<float>& rgba, int width,
                      int height, std::string* error);

}  // namespace photon
