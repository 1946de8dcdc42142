"""Blender's standard data passes (View Layer > Passes > Data: Z, Mist, Normal, Position, UV,
Object Index, Material Index): which the view layer enables, their registration, the native
settings that make the renderer write them, and a warning for enabled passes Photon cannot
produce (they keep Blender's default, zero)."""

# View layer toggle -> native pass name (as DATA_PASSES names them: Cycles' pass names).
DATA_PASS_TOGGLES = (
    ("use_pass_z", "Depth"),
    ("use_pass_mist", "Mist"),
    ("use_pass_normal", "Normal"),
    ("use_pass_position", "Position"),
    ("use_pass_uv", "UV"),
    ("use_pass_object_index", "IndexOB"),
    ("use_pass_material_index", "IndexMA"),
)

# Pass type for register_pass, as Cycles registers each.
_PASS_TYPES = {"Depth": "VALUE", "Mist": "VALUE", "IndexOB": "VALUE", "IndexMA": "VALUE",
               "Normal": "VECTOR", "Position": "VECTOR", "UV": "VECTOR"}

# World > Mist Pass falloff -> Cycles' exponent.
_MIST_FALLOFF = {"QUADRATIC": 2.0, "LINEAR": 1.0, "INVERSE_QUADRATIC": 0.5}


def enabled(native, view_layer):
    """[(name, channels, channel ids, bit)] of the data passes the view layer enables, in the
    native table's order."""
    names = {name for prop, name in DATA_PASS_TOGGLES if getattr(view_layer, prop, False)}
    return [p for p in native.DATA_PASSES if p[0] in names]


def register(engine, native, scene, view_layer):
    """Registers the enabled data passes (the compositor's Render Layers node shows them)."""
    for name, channels, chan_id, _bit in enabled(native, view_layer):
        engine.register_pass(scene, view_layer, name, channels, chan_id, _PASS_TYPES[name])


def settings(native, scene, view_layer, origin=None):
    """The native DataPassSettings for the view layer's passes and the scene's world mist."""
    out = native.DataPassSettings()
    mask = 0
    for _name, _channels, _chan_id, bit in enabled(native, view_layer):
        mask |= bit
    out.mask = mask
    world = scene.world
    mist = getattr(world, "mist_settings", None) if world is not None else None
    if mist is None:  # Cycles' film defaults without a world
        out.mist_start, out.mist_depth, out.mist_falloff = 0.0, 100.0, 1.0
    else:
        out.mist_start = float(mist.start)
        out.mist_depth = float(mist.depth)
        out.mist_falloff = _MIST_FALLOFF.get(mist.falloff, 2.0)
    if origin is not None:
        out.origin = [float(v) for v in origin]
    return out
