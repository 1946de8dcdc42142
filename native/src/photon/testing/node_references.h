// Shared by the shader-node conformance tests (*_nodes_test.cpp): a small JSON reader for the
// manifests in test_scenes/nodes/*.json, where to find that folder, EXR reading and the
// relative-or-absolute tolerance the comparisons with Cycles use.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "photon/base/math.h"

namespace photon {

// A JSON value: objects, arrays, strings, numbers, booleans and null. Object members keep the
// order of the file.
struct Json {
  enum Kind { kNull, kBool, kNumber, kString, kArray, kObject } kind = kNull;
  bool boolean = false;
  double number = 0.0;
  std::string string;
  std::vector<Json> array;
  std::vector<std::pair<std::string, Json>> object;

  // The member named key, or nullptr.
  const Json* find(const std::string& key) const;
  bool has(const std::string& key) const { return find(key) != nullptr; }
  // The member named key; throws std::out_of_range when there is none.
  const Json& at(const std::string& key) const;
};

// Parses JSON text; throws std::runtime_error on malformed input.
Json parse_json(const std::string& text);
// Reads and parses a JSON file; throws std::runtime_error when it cannot be read or parsed.
Json read_json(const std::filesystem::path& path);

// test_scenes/nodes: the PHOTON_NODE_REFS compile definition when that folder exists, else
// $PHOTON_SOURCE_DIR/test_scenes/nodes, else the first test_scenes/nodes above the working
// directory or the test binary. Empty when none is found.
std::filesystem::path node_refs_dir();

// The first three channels of an EXR as floats, 3 a pixel, top row first.
struct RgbImage {
  int width = 0, height = 0;
  std::vector<float> rgb;
  Vec3 at(size_t i) const { return {rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]}; }
  size_t size() const { return static_cast<size_t>(width) * height; }
};

// Reads path's RGB into *image; false (and an empty image) when it cannot be read.
bool read_rgb_exr(const std::filesystem::path& path, RgbImage* image);

// Every how many pixels the reference tests evaluate (PHOTON_NODE_REF_STRIDE, default 1): the
// sanitizer run sets a stride, since every case still runs all of its node's code at a fraction
// of the pixels, and the plain build checks every pixel.
int node_ref_pixel_stride();

// |got - want| relative to |want| above 1, absolute below: the conformance tests' error measure.
inline float relative_error(float got, float want) {
  return std::fabs(got - want) / std::max(1.0f, std::fabs(want));
}

// The largest |got - want| relative_error accepts within tol.
inline float tolerance_at(float tol, float want) {
  return tol * std::max(1.0f, std::fabs(want));
}

}  // namespace photon
