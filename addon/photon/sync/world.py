"""The Blender world to the native scene: a constant colour when the Background's inputs are
plain values (materials.world_color), else a shader program evaluated per direction
(native/src/photon/render/world_shader.h): an Environment or Sky Texture, any nodes before
them, and Mix / Add Shaders of Backgrounds (the Light Path "Is Camera Ray" trick included:
camera rays and lighting rays evaluate the tree with their own ray type)."""

from . import aovs as sync_aovs, nodes
from .inputs import MaterialContext
from .materials import world_color
from .shader_program import ProgramBuilder

MAX_DEPTH = 64
_EMITTERS = {'BACKGROUND', 'EMISSION'}


def _surface_source(world):
    if world is None or not world.use_nodes or world.node_tree is None:
        return None
    output = nodes.output_node(world.node_tree, 'OUTPUT_WORLD')
    surface = output.inputs.get("Surface") if output else None
    return nodes.source(surface) if surface is not None else None


def _is_constant(world):
    """Whether the world is one Background (or none) with unlinked inputs."""
    src = _surface_source(world)
    if src is None or src.node is None:
        return True
    node = src.node
    if node.type != 'BACKGROUND':
        return False
    return not any(nodes.source(node.inputs[name], src.stack).node is not None
                   for name in ("Color", "Strength"))


def _reads_ray_type(tree, seen=None):
    seen = set() if seen is None else seen
    if tree is None or tree in seen:
        return False
    seen.add(tree)
    for node in tree.nodes:
        if node.type == 'LIGHT_PATH' and not node.mute:
            return True
        if node.type == 'GROUP' and _reads_ray_type(node.node_tree, seen):
            return True
    return False


class _WorldCompiler:
    def __init__(self, world, reporter, textures):
        self.ctx = MaterialContext(world.name, reporter, textures, kind="World")
        self.builder = ProgramBuilder(self.ctx, world=True)
        self.ctx.use_program(self.builder)  # AOV inputs compile into the world's program

    def _black(self):
        return self.builder.constant([0.0, 0.0, 0.0])

    def radiance(self, socket, stack, depth=0):
        """Register of the radiance of the shader feeding `socket`."""
        src = nodes.source(socket, stack, self.ctx.links)
        node = src.node
        if node is None or depth > MAX_DEPTH:
            return self._black()
        b = self.builder
        if src.socket.type != 'SHADER':
            # Cycles turns a colour (or value) linked into a shader input into an emission of
            # it: an Environment Texture wired straight into the World Output lights the scene.
            return b.value_of(socket, stack, 'color')
        if node.type in _EMITTERS:
            color = b.value_of(node.inputs["Color"], src.stack, 'color')
            strength = b.value_of(node.inputs["Strength"], src.stack, 'float')
            out = b.constant([0.0] * 3)
            b._emit({"type": "ShaderNodeVectorMath", "enums": {"operation": "SCALE"},
                     "numbers": {}, "inputs": {"Vector": color, "Scale": strength},
                     "outputs": {"Vector": out}})
            return out
        if node.type == 'MIX_SHADER':
            fac = b.value_of(node.inputs["Fac"], src.stack, 'float')
            first = self.radiance(node.inputs[1], src.stack, depth + 1)
            second = self.radiance(node.inputs[2], src.stack, depth + 1)
            out = b.constant([0.0] * 3)
            b._emit({"type": "ShaderNodeMix",
                     "enums": {"data_type": "VECTOR", "factor_mode": "UNIFORM",
                               "blend_type": "MIX", "clamp_factor": "True",
                               "clamp_result": "False"},
                     "numbers": {}, "inputs": {"Factor_Float": fac, "A_Vector": first,
                                               "B_Vector": second},
                     "outputs": {"Result_Vector": out}})
            return out
        if node.type == 'ADD_SHADER':
            first = self.radiance(node.inputs[0], src.stack, depth + 1)
            second = self.radiance(node.inputs[1], src.stack, depth + 1)
            out = b.constant([0.0] * 3)
            b._emit({"type": "ShaderNodeVectorMath", "enums": {"operation": "ADD"},
                     "numbers": {}, "inputs": {"Vector": first, "Vector_001": second},
                     "outputs": {"Vector": out}})
            return out
        where = self.ctx.where(node, src.stack)
        self.ctx.warn_once(("world", where), f"{where} ({node.bl_idname}) cannot light the "
                                             f"world; it is rendered black")
        return self._black()


def warn_world_volume(world, reporter):
    """Photon renders no participating media yet: a World whose Volume output is connected
    (atmospheric fog) is rendered without it, and says so."""
    tree = world.node_tree if world is not None and getattr(world, "use_nodes", False) else None
    output = nodes.output_node(tree, 'OUTPUT_WORLD') if tree is not None else None
    volume = output.inputs.get("Volume") if output is not None else None
    if volume is not None and nodes.source(volume).node is not None:
        reporter.warning(f"World '{world.name}': its volume (fog) is not rendered by Photon yet; "
                         f"the scene is rendered without it")


def export_world(native_scene, world, reporter, textures, max_emission=None, aovs=None):
    """Sets the native world (`textures`: the materials' TextureTable, so an image is added
    once) and its AOV Output nodes for the view layer's AOVs `aovs` ({name: kind}); returns
    its constant colour, or [1, 1, 1] for a world with a program (what the 'no lights' warning
    looks at), and whether a program was set."""
    warn_world_volume(world, reporter)
    src = _surface_source(world)
    # As for materials, Cycles compiles AOV Output nodes only when the Surface is linked.
    outputs = sync_aovs.wanted_outputs(world.node_tree, aovs) \
        if aovs and src is not None and src.node is not None else []
    linked_aovs = any(sync_aovs.is_linked(node, stack, kind) for node, stack, kind in outputs)
    color = world_color(world, reporter, max_emission) \
        if _is_constant(world) and not linked_aovs else None
    if color is not None:
        native_scene.set_world(color)
        if outputs:  # only with a world (a scene may have none)
            ctx = MaterialContext(world.name, reporter, textures, kind="World")
            _set_aovs(native_scene, sync_aovs.read_outputs(outputs, ctx))
        return color, False
    compiler = _WorldCompiler(world, reporter, textures)
    reg = compiler.radiance(nodes.output_node(world.node_tree, 'OUTPUT_WORLD')
                            .inputs["Surface"], ())
    world_aovs = sync_aovs.read_outputs(outputs, compiler.ctx)
    program = compiler.builder.program()
    native_scene.set_world([0.0, 0.0, 0.0])
    if program is None:
        _set_aovs(native_scene, world_aovs)
        return [0.0, 0.0, 0.0], False
    try:
        native_scene.set_world_program(program, reg, _reads_ray_type(world.node_tree))
    except ValueError as error:
        reporter.warning(f"World '{world.name}': its nodes could not be compiled ({error}); "
                         f"rendering it black")
        _set_aovs(native_scene, [dict(a, value=sync_aovs.plain_value(a["value"], a["type"]))
                                 for a in world_aovs])
        return [0.0, 0.0, 0.0], False
    _set_aovs(native_scene, world_aovs)
    return [1.0, 1.0, 1.0], True


def _set_aovs(native_scene, world_aovs):
    if world_aovs:
        native_scene.set_world_aovs(world_aovs)
