// Lookups in the GGX energy tables (microfacet_albedo_integrals.h says what each holds): the
// tables Cycles 4's Multiscatter GGX and Principled BSDF v2 layering read, computed by Photon's
// own generator (native/tools/microfacet_albedo_gen.cpp) into microfacet_albedo_tables.cpp.
// Lookups interpolate linearly between grid points and clamp every coordinate to [0, 1].
#pragma once

namespace photon::microfacet_albedo {

// Directional albedo E(r, mu) of GGX reflection (F = 1), r = sqrt(alpha), mu = cos(theta_o).
float reflection_albedo(float r, float mu);
// Its cosine-weighted average over the hemisphere.
float reflection_albedo_average(float r);
// Directional albedo of the GGX dielectric interface (reflection + refraction, exact Fresnel)
// at relative IOR `eta` (either side: eta < 1 reads the tables of the inverted interface).
float glass_albedo(float r, float mu, float eta);
float glass_albedo_average(float r, float eta);
// The effective F0..F90 interpolation factor of the "real Fresnel remapped" model over a rough
// reflection of relative IOR eta (> 1; eta < 1 is read as 1 / eta as Cycles does: the z axis is
// |eta - 1| / (eta + 1)).
float schlick_ior_factor_average(float r, float mu, float eta);

// The grids (sizes per axis) and the raw tables, for the tests and the generator.
constexpr int kReflectionSize = 32;  // roughness x cosine
constexpr int kGlassSize = 16;       // roughness x cosine x IOR
extern const float kReflectionE[kReflectionSize * kReflectionSize];
extern const float kReflectionEavg[kReflectionSize];
extern const float kGlassE[kGlassSize * kGlassSize * kGlassSize];
extern const float kGlassEavg[kGlassSize * kGlassSize];
extern const float kGlassInvE[kGlassSize * kGlassSize * kGlassSize];
extern const float kGlassInvEavg[kGlassSize * kGlassSize];
extern const float kSchlickIorS[kGlassSize * kGlassSize * kGlassSize];

}  // namespace photon::microfacet_albedo
