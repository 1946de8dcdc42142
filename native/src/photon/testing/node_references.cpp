// Shared helpers of the shader-node conformance tests: JSON manifests, the references folder and
// EXR reading (see node_references.h).
#include "photon/testing/node_references.h"

#include <OpenImageIO/imagebuf.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace photon {
namespace {

namespace fs = std::filesystem;

class JsonParser {
 public:
  explicit JsonParser(const std::string& text) : s_(text) {}

  Json parse() {
    Json v = value();
    skip();
    if (pos_ != s_.size()) fail("trailing characters");
    return v;
  }

 private:
  [[noreturn]] void fail(const char* what) const {
    throw std::runtime_error(std::string("JSON: ") + what + " at " + std::to_string(pos_));
  }
  void skip() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  char peek() {
    skip();
    if (pos_ >= s_.size()) fail("unexpected end");
    return s_[pos_];
  }
  void expect(char c) {
    if (peek() != c) fail((std::string("expected '") + c + "'").c_str());
    ++pos_;
  }
  std::string str() {
    expect('"');
    std::string out;
    while (true) {
      if (pos_ >= s_.size()) fail("unterminated string");
      char c = s_[pos_++];
      if (c == '"') break;
      if (c == '\\') {
        if (pos_ >= s_.size()) fail("unterminated string");
        c = s_[pos_++];
        switch (c) {
          case 'n':
            c = '\n';
            break;
          case 't':
            c = '\t';
            break;
          case 'r':
            c = '\r';
            break;
          case 'b':
            c = '\b';
            break;
          case 'f':
            c = '\f';
            break;
          case 'u': {
            if (pos_ + 4 > s_.size()) fail("bad \\u escape");
            const unsigned code =
                static_cast<unsigned>(std::stoul(s_.substr(pos_, 4), nullptr, 16));
            pos_ += 4;
            if (code < 0x80) {
              out += static_cast<char>(code);
            } else if (code < 0x800) {
              out += static_cast<char>(0xC0 | (code >> 6));
              out += static_cast<char>(0x80 | (code & 0x3F));
            } else {
              out += static_cast<char>(0xE0 | (code >> 12));
              out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
              out += static_cast<char>(0x80 | (code & 0x3F));
            }
            continue;
          }
          default:
            break;  // '"', '\\', '/'
        }
      }
      out += c;
    }
    return out;
  }
  Json value() {
    Json v;
    const char c = peek();
    if (c == '{') {
      v.kind = Json::kObject;
      ++pos_;
      if (peek() == '}') return ++pos_, v;
      do {
        std::string key = str();
        expect(':');
        v.object.emplace_back(std::move(key), value());
      } while (peek() == ',' && ++pos_);
      expect('}');
    } else if (c == '[') {
      v.kind = Json::kArray;
      ++pos_;
      if (peek() == ']') return ++pos_, v;
      do v.array.push_back(value());
      while (peek() == ',' && ++pos_);
      expect(']');
    } else if (c == '"') {
      v.kind = Json::kString;
      v.string = str();
    } else if (s_.compare(pos_, 4, "true") == 0 || s_.compare(pos_, 5, "false") == 0) {
      v.kind = Json::kBool;
      v.boolean = s_[pos_] == 't';
      pos_ += v.boolean ? 4 : 5;
    } else if (s_.compare(pos_, 4, "null") == 0) {
      pos_ += 4;
    } else {
      v.kind = Json::kNumber;
      const char* begin = s_.c_str() + pos_;
      char* end = nullptr;
      v.number = std::strtod(begin, &end);
      if (end == begin) fail("bad value");
      pos_ += static_cast<size_t>(end - begin);
    }
    return v;
  }

  const std::string& s_;
  size_t pos_ = 0;
};

// The first folder at or above start holding test_scenes/nodes.
fs::path nodes_above(fs::path dir) {
  for (; !dir.empty(); dir = dir.parent_path()) {
    if (fs::is_directory(dir / "test_scenes" / "nodes")) return dir / "test_scenes" / "nodes";
    if (dir == dir.parent_path()) break;
  }
  return {};
}

}  // namespace

const Json* Json::find(const std::string& key) const {
  for (const auto& [k, v] : object)
    if (k == key) return &v;
  return nullptr;
}

const Json& Json::at(const std::string& key) const {
  if (const Json* v = find(key)) return *v;
  throw std::out_of_range("JSON object has no member \"" + key + "\"");
}

Json parse_json(const std::string& text) {
  return JsonParser(text).parse();
}

Json read_json(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_json(ss.str());
}

fs::path node_refs_dir() {
#ifdef PHOTON_NODE_REFS
  if (fs::is_directory(PHOTON_NODE_REFS)) return PHOTON_NODE_REFS;
#endif
  if (const char* env = std::getenv("PHOTON_SOURCE_DIR")) {
    const fs::path dir = fs::path(env) / "test_scenes" / "nodes";
    if (fs::is_directory(dir)) return dir;
  }
  std::error_code ec;
  if (fs::path dir = nodes_above(fs::current_path(ec)); !dir.empty()) return dir;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) return nodes_above(exe.parent_path());
  return {};
}

bool read_rgb_exr(const fs::path& path, RgbImage* image) {
  *image = RgbImage();
  OIIO::ImageBuf buf(path.string());
  if (!buf.read(0, 0, true, OIIO::TypeDesc::FLOAT)) return false;
  const OIIO::ImageSpec& spec = buf.spec();
  image->width = spec.width;
  image->height = spec.height;
  image->rgb.resize(image->size() * 3);
  if (buf.get_pixels(OIIO::ROI(0, spec.width, 0, spec.height, 0, 1, 0, 3), OIIO::TypeDesc::FLOAT,
                     image->rgb.data()))
    return true;
  *image = RgbImage();
  return false;
}

int node_ref_pixel_stride() {
  const char* env = std::getenv("PHOTON_NODE_REF_STRIDE");
  const int stride = env ? std::atoi(env) : 1;
  return std::max(stride, 1);
}

}  // namespace photon
