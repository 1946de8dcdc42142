#include "photon/film/pass_layout.h"

#include <algorithm>

#include "photon/film/cryptomatte.h"

namespace photon {

const std::vector<CryptoKind>& cryptomatte_kinds() {
  static const std::vector<CryptoKind> kinds = {
      {kCryptoObject, "CryptoObject"},
      {kCryptoMaterial, "CryptoMaterial"},
      {kCryptoAsset, "CryptoAsset"},
  };
  return kinds;
}

const std::vector<std::string>& light_pass_names() {
  // As the add-on registers them in Blender's render result.
  static const std::vector<std::string> names = {"Photon Direct", "Photon Indirect",
                                                 "Photon Caustics", "Photon Map"};
  return names;
}

const std::vector<DataPassInfo>& data_pass_table() {
  // Names and channels as Cycles registers them (intern/cycles/blender/addon/engine.py).
  static const std::vector<DataPassInfo> table = {
      {kPassDepth, "Depth", 1, "Z"},
      {kPassMist, "Mist", 1, "Z"},
      {kPassNormal, "Normal", 3, "XYZ"},
      {kPassPosition, "Position", 3, "XYZ"},
      {kPassUv, "UV", 3, "UVA"},
      {kPassObjectIndex, "IndexOB", 1, "X"},
      {kPassMaterialIndex, "IndexMA", 1, "X"},
      {kPassDiffuseColor, "DiffCol", 3, "RGB"},
      {kPassGlossyColor, "GlossCol", 3, "RGB"},
      {kPassTransmissionColor, "TransCol", 3, "RGB"},
      {kPassEmission, "Emit", 3, "RGB"},
      {kPassDenoisingNormal, "Denoising Normal", 3, "XYZ"},
      {kPassDenoisingAlbedo, "Denoising Albedo", 3, "RGB"},
      {kPassDenoisingDepth, "Denoising Depth", 1, "Z"},
  };
  return table;
}

int data_pass_floats(uint32_t mask) {
  int n = 0;
  for (const DataPassInfo& p : data_pass_table())
    if (mask & p.bit) n += p.channels;
  return n;
}

int data_pass_offset(uint32_t mask, uint32_t bit) {
  if (!(mask & bit)) return -1;
  int n = 0;
  for (const DataPassInfo& p : data_pass_table()) {
    if (p.bit == bit) return n;
    if (mask & p.bit) n += p.channels;
  }
  return -1;
}

std::vector<DataPassSlot> data_pass_slots(const DataPassSettings& settings) {
  std::vector<DataPassSlot> slots;
  int offset = 0;
  for (const DataPassInfo& p : data_pass_table()) {
    if (!(settings.mask & p.bit)) continue;
    slots.push_back({p.name, p.channels, p.channel_ids, offset});
    offset += p.channels;
  }
  const int layers = cryptomatte_layers(std::max(settings.cryptomatte_depth, 0));
  for (const CryptoKind& kind : cryptomatte_kinds()) {
    if (!(settings.cryptomatte & kind.bit)) continue;
    for (int layer = 0; layer < layers; ++layer) {
      const std::string index = (layer < 10 ? "0" : "") + std::to_string(layer);
      slots.push_back({kind.name + index, 4, "RGBA", offset});
      offset += 4;
    }
  }
  // As Cycles registers shader AOVs: colour RGBA, value X.
  for (const ShaderAovPass& aov : settings.aovs) {
    const int channels = aov.color ? 4 : 1;
    slots.push_back({aov.name, channels, aov.color ? "RGBA" : "X", offset});
    offset += channels;
  }
  return slots;
}

int data_pass_pixel_floats(const DataPassSettings& settings) {
  int n = 0;
  for (const DataPassSlot& slot : data_pass_slots(settings)) n += slot.channels;
  return n;
}

}  // namespace photon
