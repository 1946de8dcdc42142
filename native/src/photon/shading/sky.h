// The Sky Texture (ShaderNodeTexSky) as Blender 3.4's Cycles computes it:
//   NISHITA: single scattering in a layered atmosphere (Nishita et al. 1993, "Display of the
//     Earth Taking into Account Atmospheric Scattering"), tabulated once per node over the sky
//     dome in CIE XYZ exactly as Blender's intern/sky does (512 x 128, rows denser towards the
//     horizon), plus a limb-darkened sun disc from the sun's transmitted irradiance;
//   PREETHAM: the Perez luminance distribution with Preetham's turbidity fits (Preetham, Shirley,
//     Smits 1999, "A Practical Analytic Model for Daylight", appendix A.2).
//   HOSEK_WILKIE: the analytic sky-dome model of Hosek & Wilkie 2012 ("An Analytic Model for Full
//     Spectral Sky-Dome Radiance"), CIE XYZ version, from its published coefficient tables
//     (sky_hosek_data.*).
#pragma once

#include <string>
#include <vector>

#include "photon/shading/program.h"

namespace photon {

// ShaderNodeTexSky's sky_type, as Instruction::mode.
enum class SkyModel : uint32_t { kPreetham = 0, kHosekWilkie = 1, kNishita = 2 };

// The Nishita table's size (Blender's SkyLoader).
constexpr int kNishitaWidth = 512;
constexpr int kNishitaHeight = 128;

// Fills in.../out/mode/data for a ShaderNodeTexSky; the caller sets family and kind.
CompileStatus compile_sky_node(const NodeDesc& desc, ShaderProgram* program, Instruction* ins,
                               std::string* error);
// Radiance (scene-linear Rec.709) seen along `dir` (need not be normalized).
Vec3 eval_sky(const Instruction& ins, const ShaderProgram& program, const Vec3& dir);

// Blender's Nishita precomputation: the sky table (XYZ, kNishitaWidth x kNishitaHeight, row
// major, row 0 at the horizon) and the sun disc's XYZ radiance at its bottom and top edges.
std::vector<float> nishita_sky_table(float sun_elevation, float altitude, float air_density,
                                     float dust_density, float ozone_density);
void nishita_sun_pixels(float sun_elevation, float angular_diameter, float altitude,
                        float air_density, float dust_density, Vec3* bottom, Vec3* top);

}  // namespace photon
