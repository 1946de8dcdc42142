// Which of Blender's data passes a render writes, and their parameters (integrators/data_passes.h
// computes them). Plain data, part of RenderSettings.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "photon/base/math.h"

namespace photon {

enum DataPassBits : uint32_t {
  kPassDepth = 1u << 0,
  kPassMist = 1u << 1,
  kPassNormal = 1u << 2,
  kPassPosition = 1u << 3,
  kPassUv = 1u << 4,
  kPassObjectIndex = 1u << 5,
  kPassMaterialIndex = 1u << 6,
  kPassDiffuseColor = 1u << 7,
  kPassGlossyColor = 1u << 8,
  kPassTransmissionColor = 1u << 9,
  kPassEmission = 1u << 10,
  kPassDenoisingNormal = 1u << 11,
  kPassDenoisingAlbedo = 1u << 12,
  kPassDenoisingDepth = 1u << 13,
  kPassAllData = (1u << 14) - 1,
};

// The Cryptomatte passes (Object, Material, Asset), after the data passes in a pixel.
enum CryptomatteBits : uint32_t {
  kCryptoObject = 1u << 0,
  kCryptoMaterial = 1u << 1,
  kCryptoAsset = 1u << 2,
};

// A shader AOV of the view layer (View Layer > Shader AOV): the AOV Output nodes of that name
// write it, colour (RGBA: the value and the share of samples that wrote it) or value.
struct ShaderAovPass {
  std::string name;
  bool color = true;
};

// The data passes a render writes besides the image.
struct DataPassSettings {
  uint32_t mask = 0;  // DataPassBits
  // World > Mist Pass: start, depth, falloff exponent (Quadratic 2, Linear 1, Inverse
  // Quadratic 0.5).
  float mist_start = 5.0f, mist_depth = 25.0f, mist_falloff = 2.0f;
  // View Layer > Passes > Alpha Threshold: the single-sample passes (Depth, Position, indices,
  // Normal, UV) come from the first hit at least this opaque; 0: the first hit.
  float alpha_threshold = 0.5f;
  // Added to Position: the world origin offset the scene was synced around (far from the
  // origin, positions are sent relative to it).
  Vec3 origin{0.0f};
  uint32_t cryptomatte = 0;   // CryptomatteBits
  int cryptomatte_depth = 6;  // Blender's Levels: IDs kept per pixel (two per RGBA layer)
  // The Cryptomatte material ID of surfaces without a material (the add-on hashes the name
  // Cycles gives its default surface).
  float cryptomatte_default_material = 0.0f;
  std::vector<ShaderAovPass> aovs;  // after the Cryptomatte layers in a pixel
};

}  // namespace photon
