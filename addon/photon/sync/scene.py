"""Builds a native scene from Blender's evaluated depsgraph (Blender types stop here)."""

import time

import numpy as np

from . import object_info
from .cancel import SyncPoll
from .. import cryptomatte, data_passes, texture_cache
from . import camera as sync_camera
from . import hair as sync_hair
from . import layers as sync_layers
from . import lights as sync_lights
from . import materials as sync_materials
from . import mattes as sync_mattes
from . import mesh as sync_mesh
from . import origin as sync_origin
from . import world as sync_world


class SyncStats:
    def __init__(self):
        self.meshes = 0
        self.instances = 0
        self.triangles = 0
        self.lights = 0
        self.seconds = 0.0
        # With Persistent Data (a sync_cache.MeshCache): meshes replayed from the cache and
        # meshes read from Blender; None without it.
        self.meshes_reused = None
        self.meshes_exported = None
        # World origin offset (float64) the native scene is built around (sync_origin): world
        # positions of the native scene plus this are Blender's.
        self.origin = np.zeros(3, dtype=np.float64)
        # The Cryptomatte names of the synced objects, materials and assets (cryptomatte.Names;
        # only collected for the kinds the view layer's passes enable).
        self.cryptomatte = None
        # The MaterialTable that converted the scene's materials (the viewport converts an
        # edited material again with it).
        self.material_table = None
        # texture_cache.Redirect when the texture cache folder cannot be written and this
        # scene's image textures go to a temporary folder, else None.
        self.texture_redirect = None
        self._release = []

    def release(self):
        """Frees what the render needed until its end (textures written to a temp folder)."""
        for release in self._release:
            release()
        self._release = []


# Instances placed in the native scene per step once the loop has read them all (stacked,
# bounded, rebased, added), with a cancel polled between steps: a step of 50k took 0.25 s on
# the 2-core test machine (an 8 s sync of 300k instances), 10k keep Esc within ~0.05 s.
PLACE_CHUNK = 10_000


def sync_scene(native, depsgraph, reporter, object_instances=None, mesh_cache=None,
               test_break=None):
    """Returns (native Scene, SyncStats); call stats.release() once the render has ended.

    With `test_break` (RenderEngine.test_break) the sync stops with cancel.SyncCancelled soon
    after it turns true (Esc, or Ctrl-C in background mode; cancel.py).

    With a `mesh_cache` (sync_cache.MeshCache, kept by the engine under Persistent Data),
    meshes unchanged since the previous sync with it are replayed from it.

    When `object_instances` is a dict it is filled with object name -> list of native instance
    indices (Scene.instances) of the object's own geometry, not of instances it generates
    (particles, collection instances); lighting bakes use it to address surface points.
    """
    stats = SyncStats()
    native_scene = native.Scene()
    poll = SyncPoll(test_break)
    try:
        _sync(native, native_scene, depsgraph, reporter, stats, object_instances, mesh_cache,
              poll)
        return native_scene, stats
    except BaseException:
        poll.drain()  # Blender's instance lists would leak
        if mesh_cache is not None:
            # The scene is dropped (cancelled, or an error): the kept meshes lent to it return.
            mesh_cache.reclaim(native_scene)
        stats.release()
        raise


def _sync(native, native_scene, depsgraph, reporter, stats, object_instances, mesh_cache, poll):
    """Fills `native_scene` and `stats` from the depsgraph; `poll` (a SyncPoll) is called
    after each slow step and polls as it reads the instances."""
    t0 = time.perf_counter()
    export_mesh = sync_mesh.export_object_mesh
    if mesh_cache is not None:
        mesh_cache.begin(depsgraph)
        export_mesh = mesh_cache.export
    scene = depsgraph.scene
    render_mode = getattr(depsgraph, "mode", 'RENDER') == 'RENDER'
    # Shader AOVs are final-render passes: the viewport compiles no AOV Output node.
    aovs = data_passes.shader_aovs(native, scene, depsgraph.view_layer) if render_mode else {}
    materials = sync_materials.MaterialTable(native_scene, reporter,
                                             getattr(native, "TexturePixels", None), aovs)
    stats._release.append(materials.release)
    stats.material_table = materials

    mesh_index = {}        # data identity -> native mesh index (None: no triangles)
    mesh_bounds = {}       # native mesh index -> object-space (lo, hi), float64
    bounds = sync_origin.SceneBounds()  # world bounds of the geometry, for the origin offset
    lights = []            # add_light arguments, world matrices in float64 until rebased
    # (mesh index, slot tuple, visibility, mattes) -> [(4x4 matrix, owner or None)]
    pending = {}
    mattes = sync_mattes.MatteFlags(depsgraph)
    unsupported = {}       # object type -> object names
    layer_visibility = sync_layers.LayerVisibility(native, depsgraph, reporter)
    override = sync_layers.material_override(depsgraph)
    hair = []              # (mesh index, slots, visibility, mattes) of hair ribbons (world space)
    hair_view = None       # the camera the ribbons face, read once the first hair shows up
    hair_strands = {}      # (object, particle system) -> strands, shared by its instances
    has_hair = {}          # object name -> whether it has hair systems to render
    crypto = stats.cryptomatte = cryptomatte.Names.for_view_layer(depsgraph.view_layer)

    def crypto_ids(obj):
        """(object ID, asset ID) of an instance of `obj`, or None without Cryptomatte passes."""
        if not crypto.any():
            return None
        return (crypto.id("CryptoObject", obj.name),
                crypto.id("CryptoAsset", cryptomatte.asset_name(obj)))

    def place_hair(points):
        """Anchor of hair ribbons with these world points (zero near the origin)."""
        hair_bounds = sync_origin.SceneBounds()
        hair_bounds.add_points(points)
        bounds.add(hair_bounds.lo, hair_bounds.hi)
        return hair_bounds.origin()

    for inst in poll.instances(depsgraph):
        # Instance items die when iteration moves on: use them only inside this body.
        obj = inst.object
        obj_type = obj.type
        if obj_type == 'LIGHT':
            arguments = sync_lights.light_arguments(native, obj, inst.matrix_world, reporter)
            if arguments is not None:
                lights.append(arguments)
                stats.lights += 0 if arguments.get("portal") else 1
            continue
        hair_here = obj_type == 'CURVES'
        if not hair_here and inst.show_particles and obj_type == 'MESH':
            # Once per object: a scene of many instances of one mesh asks many times.
            name = obj.name
            if name not in has_hair:
                has_hair[name] = sync_hair.has_hair(obj, render_mode)
            hair_here = has_hair[name]
        if hair_here:
            hair_view = hair_view or sync_hair.HairView(scene, depsgraph)
            slots = materials.slot_indices(obj)
            if obj_type == 'CURVES':
                made = [sync_hair.curves_hair(native_scene, obj, inst.matrix_world, hair_view,
                                              slots, reporter, place_hair)]
            else:
                relocate = (sync_hair.relocation(inst.matrix_world, obj.matrix_world)
                            if inst.is_instance else None)
                made = [] if relocate is False else sync_hair.particle_hair(
                    native_scene, obj, render_mode, hair_view, slots, reporter, relocate,
                    hair_strands, place_hair, poll)
            poll()  # strands may have taken seconds to read
            visibility = layer_visibility.apply(inst, obj,
                                                sync_lights.visibility_bits(native, obj))
            for index, triangles, hair_slots, anchor in filter(None, made):
                stats.meshes += 1
                stats.triangles += triangles
                if override is not None:
                    hair_slots = [materials.index(override)] * len(hair_slots)
                hair.append((index, hair_slots, visibility,
                             mattes.of(obj, inst.parent if inst.is_instance else None), anchor,
                             crypto_ids(obj)))
            if obj_type == 'CURVES':
                continue
        if obj_type in sync_mesh.UNSUPPORTED_GEOMETRY_TYPES:
            unsupported.setdefault(obj_type, set()).add(obj.name)
            continue
        if not sync_mesh.is_geometry(obj):
            continue
        if not inst.is_instance and not inst.show_self:
            continue
        # The evaluated data block identifies shared geometry: every instance of one mesh
        # (particles, geometry nodes, linked duplicates) maps to one native mesh and one BVH.
        if override is None:
            slots = tuple(materials.slot_indices(obj))
        else:  # the view layer's Material Override replaces every slot, as in Cycles
            slots = (materials.index(override),) * max(1, len(obj.material_slots))
        # Named attributes the slots' shader programs read are exported with the mesh (a mesh
        # shared by objects whose materials read different ones is exported once per set).
        requests = materials.attribute_requests(slots)
        key = (obj.data.as_pointer(), tuple(sorted(requests)))
        if key not in mesh_index:
            name = obj.name

            def on_missing(missing, name=name, requests=requests):
                materials.report_missing_attributes(name, missing, requests)
            index, triangles, local = export_mesh(native_scene, obj, reporter, tuple(requests),
                                                  on_missing)
            mesh_index[key] = index
            if index is not None:
                mesh_bounds[index] = local
                stats.meshes += 1
                stats.triangles += triangles
            poll()  # a big mesh takes a good part of a second
        index = mesh_index[key]
        if index is None:
            continue
        visibility = layer_visibility.apply(inst, obj, sync_lights.visibility_bits(native, obj))
        owner = None if inst.is_instance else obj.name
        matte = mattes.of(obj, inst.parent if inst.is_instance else None)
        pending.setdefault((index, slots, visibility, matte), []).append(
            (np.array(inst.matrix_world, dtype=np.float64), owner, _object_info(inst, obj),
             crypto_ids(obj)))

    if mesh_cache is not None:
        mesh_cache.end()
        stats.meshes_reused, stats.meshes_exported = mesh_cache.reused, mesh_cache.exported

    # The world origin offset, once every world-space quantity is known in double precision.
    stacked = _stacked_matrices(pending, poll)
    for key, chunks in stacked.items():
        for matrices in chunks:
            bounds.add_instances(*mesh_bounds[key[0]], matrices)
            poll()
    origin = stats.origin = bounds.origin()
    if origin.any():
        reporter.info(f"world space rebased by ({origin[0]:.9g}, {origin[1]:.9g}, "
                      f"{origin[2]:.9g}) m to keep 32-bit float precision")

    for arguments in lights:
        arguments["matrix"] = sync_origin.rebased_matrix(arguments["matrix"], origin)
        if arguments.pop("portal", False):
            native_scene.add_portal(**arguments)
        else:
            native_scene.add_light(**arguments)

    for key, entries in pending.items():
        for start, matrices in zip(range(0, len(entries), PLACE_CHUNK), stacked[key]):
            stats.instances += _add_instances(native_scene, key, matrices, origin,
                                              entries[start:start + PLACE_CHUNK],
                                              object_instances)
            poll()

    for index, slots, visibility, (holdout, catcher), anchor, ids in hair:
        # Ribbons are stored relative to their anchor: placed back at anchor - origin.
        placement = np.identity(4, dtype=np.float64)
        placement[:3, 3] = anchor
        first = native_scene.instance_count
        stats.instances += native_scene.add_instances(
            index, sync_origin.rebased_matrix(placement, origin)[None], slots, visibility,
            holdout=holdout, shadow_catcher=catcher)
        _set_cryptomatte(native_scene, first, [ids])
    if crypto.any():
        for index, name in materials.names.items():
            name = cryptomatte.DEFAULT_MATERIAL if name is None else name
            native_scene.set_material_cryptomatte(index, crypto.id("CryptoMaterial", name))

    for obj_type, names in sorted(unsupported.items()):
        shown = ", ".join(sorted(names)[:5]) + (" ..." if len(names) > 5 else "")
        reporter.warning(f"{obj_type.title()} objects are not supported yet and were skipped: "
                         f"{shown}")

    sync_camera.export_camera(native_scene, scene, depsgraph, reporter, origin=origin)
    world, _ = sync_world.export_world(native_scene, scene.world, reporter, materials.textures,
                                       getattr(native, "MAX_EMISSION", None), aovs)
    poll()
    if native_scene.texture_count:
        # Where the session converts the images (it reads the folder when it starts).
        stats.texture_redirect = texture_cache.prepare()

    if stats.triangles == 0:
        reporter.warning("The scene has no renderable geometry")
    if stats.lights == 0 and max(world) <= 0.0:
        reporter.warning("The scene has no lights and a black world: only emissive surfaces will show")
    stats.seconds = time.perf_counter() - t0


def _stacked_matrices(pending, poll):
    """{key: [(n, 4, 4) float64 matrices of pending[key] in chunks of PLACE_CHUNK]}: a million
    instances take most of a second to stack, so a cancel is seen between chunks."""
    stacked = {}
    for key, entries in pending.items():
        chunks = stacked[key] = []
        for start in range(0, len(entries), PLACE_CHUNK):
            chunks.append(np.stack([entry[0] for entry in entries[start:start + PLACE_CHUNK]]))
            poll()
    return stacked


def _add_instances(native_scene, key, matrices, origin, entries, object_instances):
    """Adds the instances `entries` of one pending key (their world `matrices`) to the native
    scene, with their Object Info and Cryptomatte IDs; returns how many were added."""
    index, slots, visibility, (holdout, catcher) = key
    first = native_scene.instance_count
    added = native_scene.add_instances(
        index, sync_origin.rebased_matrices(matrices, origin), list(slots), visibility,
        holdout=holdout, shadow_catcher=catcher)
    _set_object_info(native_scene, first, [entry[2] for entry in entries])
    _set_cryptomatte(native_scene, first, [entry[3] for entry in entries])
    if object_instances is not None:
        for offset, (_, owner, _, _) in enumerate(entries):
            if owner is not None:
                object_instances.setdefault(owner, []).append(first + offset)
    return added


def _object_info(inst, obj):
    """(colour with alpha, pass index, random) of an instance for the Object Info node, as
    Cycles sets them: instances keep the depsgraph's random_id, objects hash their name."""
    random_id = (inst.random_id if inst.is_instance else
                 object_info.hash_uint2(object_info.hash_string(obj.name), 0))
    color = tuple(float(c) for c in obj.color[:4])
    return color, float(obj.pass_index), (random_id & 0xFFFFFFFF) / 0xFFFFFFFF


def _set_cryptomatte(native_scene, first, ids):
    """Cryptomatte object and asset IDs of instances first.. (ids: (object, asset) or None)."""
    if ids and ids[0] is not None:
        native_scene.set_instance_cryptomatte(first, [i[0] for i in ids], [i[1] for i in ids])


def _set_object_info(native_scene, first, infos):
    """Object Info of instances first.. in runs of equal colour and pass index."""
    start = 0
    while start < len(infos):
        color, pass_index = infos[start][0], infos[start][1]
        end = start + 1
        while end < len(infos) and infos[end][0] == color and infos[end][1] == pass_index:
            end += 1
        if color != (1.0, 1.0, 1.0, 1.0) or pass_index != 0.0 or any(
                info[2] for info in infos[start:end]):
            native_scene.set_instance_info(first + start, list(color[:3]),
                                           [info[2] for info in infos[start:end]], pass_index,
                                           color[3])
        start = end
