// Writing RGBA float images through OpenImageIO (EXR stays linear float).
#pragma once

#include <string>
#include <vector>

namespace photon {

bool write_rgba_image(const std::string& path, const std::vector<float>& rgba, int width,
                      int height, std::string* error);

}  // namespace photon
