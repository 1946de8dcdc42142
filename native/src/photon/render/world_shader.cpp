#include "photon/render/world_shader.h"

#include <algorithm>
#include <cmath>

#include "photon/scene/material.h"
#include "photon/shading/program_eval.h"

namespace photon {

Vec3 world_radiance(const World& world, const Vec3& direction, uint32_t ray_flags,
                    const TextureSet* textures) {
  if (world.program.empty() || world.radiance_reg < 0) return world.color;
  ShaderGlobals g;
  g.is_background = true;
  const float len = length(direction);
  const Vec3 d = len > 0.0f ? direction / len : Vec3(0.0f, 0.0f, 1.0f);
  // Cycles' background shading point: P is the direction, N, Ng and I point back along it.
  g.p = d;
  g.n = g.ng = g.incoming = -d;
  g.generated = d;
  g.ray_flags = ray_flags;
  g.textures = textures;
  ProgramRegisters registers(world.program);
  run_program(world.program, g, registers.data());
  const Vec3 v = load3(registers.data(), world.radiance_reg);
  const ParamRange r = emitter_range();
  auto clamp = [&r](float x) { return std::isfinite(x) ? std::clamp(x, 0.0f, r.hi) : 0.0f; };
  return {clamp(v.x), clamp(v.y), clamp(v.z)};
}

}  // namespace photon
