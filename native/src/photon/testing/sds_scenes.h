// Scenes whose light reaches the camera over specular-diffuse-specular (SDS) paths, which path
// tracing with next-event estimation cannot sample from a point light and samples badly from a
// small one: the progressive integrators (SPPM, VCM) are tested and benchmarked on them. Every
// light is a small emissive sphere (a mesh, so every integrator and Cycles treat it alike), and
// shadow rays stop at glass, so the light behind glass arrives only as photons, merged light
// subpaths or camera paths that happen to hit the emitter.
//
// test_scenes/sds.py builds the same scenes in Blender (same triangles, normals, materials and
// camera); test_scenes/sds/ holds their references (test_scenes/sds/make_references.py).
#pragma once

#include <string>
#include <vector>

#include "photon/scene/scene.h"

namespace photon {

// (a) A thick glass shell (IOR 1.5, radii 0.4 and 0.25: a ball with an air cavity) holding a
// small emissive sphere above the cavity's centre, in the Cornell room (white, red and green
// walls, open towards the camera). All light leaves through the glass: the walls are lit by
// caustics, and the ball shows them refracted (E S D S L).
Scene make_sds_glass_light();

// (b) A glass ball focusing a small emissive sphere onto a white floor, in front of a flat
// mirror; the camera looks at the mirror and sees the caustic only in it (E S D S S L).
Scene make_sds_mirror_caustic();

// (c) A pool: a closed glass slab (IOR 1.33) with a wavy top (a displaced 128 x 128 grid with
// analytic normals) over a checkered floor, a small emissive sphere above, the camera looking
// down through the surface at the caustics on the floor (E S S D S S L).
Scene make_sds_pool();

// The SDS scenes by name ("glass_light", "mirror_caustic", "pool"); false for another name.
bool make_sds_scene(const std::string& name, Scene* scene);
const std::vector<std::string>& sds_scene_names();

// A closed slab over [-half, half]^2 from z = bottom to a wavy top at z = top + the pool's
// waves, the top a grid of cells x cells squares (two triangles each, split along the diagonal
// from (i, j) to (i + 1, j + 1)) with the waves' analytic normals as corner normals; flat
// bottom and sides. Faces point out.
Mesh make_wavy_slab(float half, float bottom, float top, int cells);

// A 24 x 12 UV sphere whose material is an Emission closure of `radiance`: a small light that
// every integrator (and Cycles) samples as emissive triangles.
void add_emissive_sphere(Scene* scene, const Vec3& center, float radius, float radiance);

}  // namespace photon
