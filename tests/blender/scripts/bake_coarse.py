"""Bakes the Cornell box into colour attributes, its walls subdivided `cuts` times (0: as built,
four corners a wall), with few photons; for test_bake_coarse.py, which reads the warnings."""


import bpy

import builders
import harness


def main(cuts):
    scene = builders.cornell_box(width=32, height=32, samples=1)
    scene.photon.photons = 5000
    scene.photon.caustic_photons = 0
    scene.photon.bake_target = 'COLOR_ATTRIBUTE'
    scene.photon.bake_samples = 1
    for obj in [o for o in scene.objects if o.type == 'MESH']:
        if int(cuts):
            builders.subdivide(obj, int(cuts))
    return {"bake": sorted(bpy.ops.photon.bake_lighting())}


harness.run(main)
