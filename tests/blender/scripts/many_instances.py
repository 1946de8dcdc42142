"""Builds a scene whose sync is long: COUNT geometry-node instances of a small cube spread over
a grid in front of the camera, under a sun, and saves it as a .blend.
Args: COUNT BLEND_PATH

Blender evaluates the node tree before render() is called; the add-on then walks every instance
in depsgraph.object_instances (tens of microseconds each in Python), so a million instances
take most of a minute to sync."""

import math

import bpy

import builders
import harness


def instancing_tree(count):
    """A geometry-node tree putting a 2 cm cube on each point of a square grid of `count`
    points (rounded to a square) 4 m wide."""
    tree = bpy.data.node_groups.new("ManyCubes", 'GeometryNodeTree')
    builders.new_group_socket(tree, 'INPUT', 'NodeSocketGeometry', "Geometry")
    builders.new_group_socket(tree, 'OUTPUT', 'NodeSocketGeometry', "Geometry")
    nodes, links = tree.nodes, tree.links
    output = nodes.new("NodeGroupOutput")
    side = max(2, round(math.sqrt(count)))
    grid = nodes.new("GeometryNodeMeshGrid")
    grid.inputs["Size X"].default_value = 4.0
    grid.inputs["Size Y"].default_value = 4.0
    grid.inputs["Vertices X"].default_value = side
    grid.inputs["Vertices Y"].default_value = side
    cube = nodes.new("GeometryNodeMeshCube")
    cube.inputs["Size"].default_value = (0.02, 0.02, 0.02)
    instance = nodes.new("GeometryNodeInstanceOnPoints")
    links.new(grid.outputs["Mesh"], instance.inputs["Points"])
    links.new(cube.outputs["Mesh"], instance.inputs["Instance"])
    links.new(instance.outputs["Instances"], output.inputs["Geometry"])
    return tree, side * side


def main(count, blend_path):
    scene = builders.reset_scene(width=32, height=32)
    scene.photon.integrator = 'RAY_TRACE'
    scene.photon.samples = 1
    holder = builders.link(bpy.data.objects.new("Cubes", bpy.data.meshes.new("Cubes")))
    holder.data.materials.append(builders.diffuse_material("Grey", (0.5, 0.5, 0.5)))
    modifier = holder.modifiers.new("ManyCubes", 'NODES')
    modifier.node_group, instances = instancing_tree(int(count))
    builders.camera(location=(0, 0, 6), rotation=(0, 0, 0))
    builders.light("Sun", 'SUN', 3.0, (0, 0, 5))
    bpy.ops.wm.save_as_mainfile(filepath=blend_path)
    return {"instances": instances}


harness.run(main)
