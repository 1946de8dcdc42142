"""Builds a scene with modifiers, geometry-nodes instances, text, a metaball, a NURBS surface, a
linked duplicate and every light type, syncs it, and reports the native scene's counts."""

import bpy

import builders
import harness


def scatter_node_group(count_x, count_y):
    ng = bpy.data.node_groups.new("Scatter", 'GeometryNodeTree')
    builders.new_group_socket(ng, 'INPUT', 'NodeSocketGeometry', "Geometry")
    builders.new_group_socket(ng, 'OUTPUT', 'NodeSocketGeometry', "Geometry")
    nodes, links = ng.nodes, ng.links
    nodes.new('NodeGroupInput')
    out = nodes.new('NodeGroupOutput')
    grid = nodes.new('GeometryNodeMeshGrid')
    grid.inputs['Vertices X'].default_value = count_x
    grid.inputs['Vertices Y'].default_value = count_y
    cube = nodes.new('GeometryNodeMeshCube')
    cube.inputs['Size'].default_value = (0.1, 0.1, 0.1)
    scatter = nodes.new('GeometryNodeInstanceOnPoints')
    links.new(grid.outputs['Mesh'], scatter.inputs['Points'])
    links.new(cube.outputs['Mesh'], scatter.inputs['Instance'])
    links.new(scatter.outputs['Instances'], out.inputs[0])
    return ng


def main():
    from photon import _photon, report, sync
    scene = builders.reset_scene()
    builders.camera()

    cube = builders.box("SubdivCube", (-0.5, -0.5, -0.5), (0.5, 0.5, 0.5))
    mod = cube.modifiers.new("Subsurf", 'SUBSURF')
    mod.levels = mod.render_levels = 1                        # 6 quads -> 24 quads -> 48 tris

    plane = builders.quad("ArrayPlane", (0, 0, 0), (1, 0, 0), (0, 1, 0))
    mod = plane.modifiers.new("Array", 'ARRAY')
    mod.count = 3
    mod.relative_offset_displace = (1.5, 0, 0)                # 3 separate quads -> 6 tris

    scatter = builders.mesh_object("Scatter", [(0, 0, 0)], [])
    mod = scatter.modifiers.new("GN", 'NODES')
    mod.node_group = scatter_node_group(10, 10)              # 100 instances of a 12-tri cube

    shared_a = builders.box("SharedA", (2, 2, 0), (3, 3, 1))
    shared_b = bpy.data.objects.new("SharedB", shared_a.data)  # linked duplicate
    shared_b.location = (0, 4, 0)
    builders.link(shared_b)

    text = bpy.data.curves.new("Text", 'FONT')
    text.body = "Hi"
    builders.link(bpy.data.objects.new("Text", text))

    meta = bpy.data.metaballs.new("Meta")
    meta.elements.new()
    builders.link(bpy.data.objects.new("Meta", meta)).location = (4, 0, 0)
    bpy.ops.surface.primitive_nurbs_surface_sphere_add(location=(-4, 0, 0))

    builders.light("Point", 'POINT', 100, (0, 0, 3), shadow_soft_size=0.1)
    builders.light("Spot", 'SPOT', 100, (1, 0, 3), spot_size=1.0, spot_blend=0.2)
    builders.light("Sun", 'SUN', 3, (0, 0, 5), angle=0.05)
    for shape in ('SQUARE', 'RECTANGLE', 'DISK', 'ELLIPSE'):
        builders.light(f"Area{shape}", 'AREA', 50, (0, 0, 2), shape=shape, size=1.0, size_y=0.5)
    builders.light("ZeroPower", 'POINT', 0.0, (0, 0, 1))

    depsgraph = bpy.context.evaluated_depsgraph_get()
    reporter = report.Reporter()
    native_scene, stats = sync.sync_scene(_photon, depsgraph, reporter)
    return {
        "mesh_count": native_scene.mesh_count,
        "instance_count": native_scene.instance_count,
        "triangle_count": native_scene.triangle_count,
        "light_count": native_scene.light_count,
        "material_count": native_scene.material_count,
        "sync_seconds": stats.seconds,
        "warnings": reporter.warnings,
    }


harness.run(main)
