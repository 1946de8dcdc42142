#include "photon/base/check.h"

namespace photon {

void check_failed(const char* condition, const char* file, int line) {
  // The path relative to the source tree is enough to find the line.
  const std::string path = file;
  const size_t src = path.rfind("photon/");
  throw CheckFailure("internal check failed: " + std::string(condition) + " (" +
                     (src == std::string::npos ? path : path.substr(src)) + ":" +
                     std::to_string(line) + ")");
}

}  // namespace photon
