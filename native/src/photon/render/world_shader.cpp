#include "photon/render/world_shader.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "photon/scene/material.h"
#include "photon/shading/program_eval.h"

namespace photon {

namespace {

// Cycles' background shading point: P is the direction, N, Ng and I point back along it.
ShaderGlobals background_globals(const Vec3& direction, uint32_t ray_flags,
                                 const TextureSet* textures) {
  ShaderGlobals g;
  g.is_background = true;
  const float len = length(direction);
  const Vec3 d = len > 0.0f ? direction / len : Vec3(0.0f, 0.0f, 1.0f);
  g.p = d;
  g.n = g.ng = g.incoming = -d;
  g.generated = d;
  g.ray_flags = ray_flags;
  g.textures = textures;
  return g;
}

}  // namespace

Vec3 world_radiance(const World& world, const Vec3& direction, uint32_t ray_flags,
                    const TextureSet* textures) {
  if (world.program.empty() || world.radiance_reg < 0) return world.color;
  const ShaderGlobals g = background_globals(direction, ray_flags, textures);
  ProgramRegisters registers(world.program);
  run_program(world.program, g, registers.data());
  const Vec3 v = load3(registers.data(), world.radiance_reg);
  const ParamRange r = emitter_range();
  auto clamp = [&r](float x) { return std::isfinite(x) ? std::clamp(x, 0.0f, r.hi) : 0.0f; };
  return {clamp(v.x), clamp(v.y), clamp(v.z)};
}

void world_aovs(const World& world, const Vec3& direction, const TextureSet* textures, Vec3* out) {
  if (world.aovs.empty()) return;
  std::optional<ProgramRegisters> registers;
  if (!world.program.empty()) {
    registers.emplace(world.program);
    run_program(world.program, background_globals(direction, kRayCamera, textures),
                registers->data());
  }
  const auto finite = [](float x) { return std::isfinite(x) ? x : 0.0f; };
  for (size_t k = 0; k < world.aovs.size(); ++k) {
    const Input& in = world.aovs[k].value;
    const Vec3 v = in.reg >= 0 && registers ? load3(registers->data(), in.reg) : in.value;
    out[k] = Vec3(finite(v.x), world.aovs[k].color ? finite(v.y) : 0.0f,
                  world.aovs[k].color ? finite(v.z) : 0.0f);
  }
}

}  // namespace photon
