// The fingerprint of everything an integrator's preparation depends on, stored in a
// prepared-state file (prepared_state_file.h) and compared before the file is loaded: a state
// prepared for another scene, frame or setting is refused instead of rendering wrong pixels.
//
// It covers the scene's content as the renderer sees it: every mesh (positions, triangles,
// normals, UVs, material slots, texture space, attributes), instance (mesh, transform,
// materials, visibility, mattes, Object Info values), material (closures, inputs, shader
// programs), light, the camera and the world (colour and node program), and each image
// texture by the content key of its pixels (texture_convert.h) and its sampling settings.
// Of the render settings it covers the frame size and every render parameter (render_params.h)
// except those that cannot change a pixel (threads, tile size) or belong to the viewport
// (preview samples); the render border is not covered, so every band of a frame shares its
// state. Anything added to the scene or the parameter schemas must enter here too (the
// parameters do by themselves).
#pragma once

#include <cstdint>
#include <string>

#include "photon/integrators/integrator.h"

namespace photon {

class TextureSet;

// The format version (prepared_state_file.h) is part of the fingerprint. Returns false with
// `why_not` when the scene holds something that cannot be fingerprinted: a world whose radiance
// is a C++ callback (World::radiance, set only by programs that build scenes in code).
bool prepared_state_fingerprint(const Scene& scene, const RenderSettings& settings,
                                const TextureSet& textures, uint64_t* fingerprint,
                                std::string* why_not);

}  // namespace photon
