"""Builds a Cornell box with a ball and, by CASE, hair on it, and saves it as a .blend.
Args: CASE BLEND_PATH

CASE: "bald" (the ball alone); "particle_hair" (a hair particle system with children, its
strands in the ball's second material slot, a red emission); "instanced_hair" (that furry ball
shown only through a collection instance 0.7 m to the left); "sparse_hair" (60 strands, no
children) and "sparse_hair_thick" (the same strands twice as thick); "curves" (a Curves object
of random strands in a red emission material); "curves_nan" (those strands with NAN_POINTS
points NaN or infinite, shown twice: by the object and by a collection instance of it);
"motion_blur" (the bald scene with motion blur on and the ball moving through the frame).
"""

import bpy
import numpy as np

import builders
import harness


def base():
    scene = builders.cornell_box(width=64, height=64, samples=4)
    # Ray tracing keeps these renders to a second or two; hair goes through the same mesh path
    # for every integrator.
    scene.photon.integrator = 'RAY_TRACE'
    white = bpy.data.materials["White"]
    ball = builders.uv_sphere("Ball", (0.35, -0.35, 0.85), 0.2, material=white)
    ball.rotation_euler = (0.5, 0.3, 0.2)  # hair roots leave the sphere's axes
    return scene, ball


def red_emission(name):
    """Hair pixels are then red whatever the lighting: the test finds them by colour."""
    return builders.shader_material(name, "ShaderNodeEmission", Color=(1.0, 0.0, 0.0, 1.0),
                                    Strength=2.0)


def particle_hair(ball, radius_scale=0.01, count=300, children=5):
    red = red_emission("HairRed")
    ball.data.materials.append(red)
    mod = ball.modifiers.new("Hair", 'PARTICLE_SYSTEM')
    settings = mod.particle_system.settings
    settings.type = 'HAIR'
    settings.count = count
    settings.hair_length = 0.25
    settings.material = 2           # the ball's second slot: red
    settings.root_radius = 1.0
    settings.tip_radius = 0.0
    settings.radius_scale = radius_scale  # 0.01: 5 mm at the root, as Cycles reads it
    settings.child_type = 'INTERPOLATED' if children else 'NONE'
    settings.child_nbr = 2
    settings.rendered_child_count = children
    mod.particle_system.seed = 1


def curves():
    red = red_emission("CurvesRed")
    bpy.ops.object.curves_random_add(location=(-0.3, -0.5, 1.2))
    obj = bpy.context.active_object
    # The operator's strands span about 4 m: scaled to fit the box (radii scale with them).
    obj.scale = (0.2, 0.2, 0.2)
    obj.data.materials.append(red)
    return obj


NAN_POINTS = 7  # of the 4000 points of curves_random_add's 500 strands


def break_points(obj):
    """Makes NAN_POINTS of a Curves object's points NaN or infinite, in different strands."""
    curves = obj.data
    positions = np.empty(len(curves.points) * 3, dtype=np.float32)
    curves.position_data.foreach_get("vector", positions)
    positions = positions.reshape(-1, 3)
    broken = np.arange(NAN_POINTS) * 41  # 8 points a strand: one point in each of 7 strands
    positions[broken, 0] = np.nan
    positions[broken[-1], 1] = np.inf
    curves.position_data.foreach_set("vector", positions.ravel())
    curves.update_tag()


def instance_of(obj, name, offset):
    """Shows `obj` again through a collection instance moved by `offset`."""
    collection = bpy.data.collections.new(name)
    collection.objects.link(obj)
    instance = builders.link(bpy.data.objects.new(f"{name}Instance", None))
    instance.instance_type = 'COLLECTION'
    instance.instance_collection = collection
    instance.location = offset


def main(case, blend_path):
    scene, ball = base()
    if case == "particle_hair":
        particle_hair(ball)
    elif case == "instanced_hair":
        # The furry ball only through a collection instance, 0.7 m to the left and turned.
        particle_hair(ball)
        collection = bpy.data.collections.new("Fur")
        collection.objects.link(ball)
        scene.collection.objects.unlink(ball)
        empty = builders.link(bpy.data.objects.new("FurInstance", None))
        empty.instance_type = 'COLLECTION'
        empty.instance_collection = collection
        empty.location = (-0.7, 0.0, 0.0)
    elif case in ("sparse_hair", "sparse_hair_thick"):
        # Few strands, rarely overlapping: their covered area follows their width.
        particle_hair(ball, radius_scale=0.04 if case == "sparse_hair_thick" else 0.02,
                      count=60, children=0)
    elif case == "curves":
        curves()
    elif case == "curves_nan":
        obj = curves()
        break_points(obj)
        instance_of(obj, "Strands", (0.6, 0.0, 0.0))
    elif case == "motion_blur":
        scene.render.use_motion_blur = True
        ball.location = (0.0, -0.35, 0.85)
        ball.keyframe_insert("location", frame=0)
        ball.location = (0.6, -0.35, 0.85)
        ball.keyframe_insert("location", frame=2)
    elif case != "bald":
        raise ValueError(f"unknown case {case}")
    bpy.ops.wm.save_as_mainfile(filepath=blend_path)
    return {"saved": blend_path}


harness.run(main)
