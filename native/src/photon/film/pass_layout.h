// The passes a render writes besides Combined, named and laid out as Blender registers them: the
// light passes (a sample's light split by the path that carried it) and the data passes
// (geometry, colours, denoising features, Cryptomatte), with Cycles' names and channels.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "photon/film/data_pass_settings.h"

namespace photon {

// The light passes in the order of RadianceSample's fields (radiance_sample.h).
const std::vector<std::string>& light_pass_names();

// The Cryptomatte kinds in Blender's pass order, with their pass names.
struct CryptoKind {
  uint32_t bit;
  const char* name;
};
const std::vector<CryptoKind>& cryptomatte_kinds();

// A pass as Blender registers it: name, channel count and channel letters.
struct DataPassInfo {
  uint32_t bit;
  const char* name;
  int channels;
  const char* channel_ids;
};

// Every data pass, in the order their floats follow each other in a pixel.
const std::vector<DataPassInfo>& data_pass_table();
// Floats per pixel for the passes in `mask`.
int data_pass_floats(uint32_t mask);
// Offset of `bit`'s first float within a pixel of `mask` (-1 when `bit` is not in `mask`).
int data_pass_offset(uint32_t mask, uint32_t bit);

// A pass within a pixel's floats (data passes, then Cryptomatte layers, then shader AOVs), named
// and laid out as Blender registers it ("CryptoObject00", 4 channels "RGBA").
struct DataPassSlot {
  std::string name;
  int channels = 0;
  std::string channel_ids;
  int offset = 0;
};

// Every pass `settings` asks for, in pixel order.
std::vector<DataPassSlot> data_pass_slots(const DataPassSettings& settings);
// Floats per pixel of every pass `settings` asks for.
int data_pass_pixel_floats(const DataPassSettings& settings);

}  // namespace photon
