"""Blender's standard passes beyond Combined (View Layer > Passes > Data: Z, Mist, Normal,
Position, UV, Object Index, Material Index, Denoising Data; > Light: Diffuse / Glossy /
Transmission Color, Emission; > Cryptomatte: Object, Material, Asset; > Shader AOV): which the
view layer enables, their registration, the native settings that make the renderer write them,
and one warning naming the enabled passes Photon does not render."""

from . import cryptomatte

# View layer toggle -> native pass name (as DATA_PASSES names them: Cycles' pass names).
DATA_PASS_TOGGLES = (
    ("use_pass_z", "Depth"),
    ("use_pass_mist", "Mist"),
    ("use_pass_normal", "Normal"),
    ("use_pass_position", "Position"),
    ("use_pass_uv", "UV"),
    ("use_pass_object_index", "IndexOB"),
    ("use_pass_material_index", "IndexMA"),
    ("use_pass_diffuse_color", "DiffCol"),
    ("use_pass_glossy_color", "GlossCol"),
    ("use_pass_transmission_color", "TransCol"),
    ("use_pass_emit", "Emit"),
)

# View layer toggles of passes Photon does not render, with their labels in View Layer > Passes.
_UNSUPPORTED_TOGGLES = (
    ("use_pass_vector", "Vector"),
    ("use_pass_diffuse_direct", "Diffuse Direct"),
    ("use_pass_diffuse_indirect", "Diffuse Indirect"),
    ("use_pass_glossy_direct", "Glossy Direct"),
    ("use_pass_glossy_indirect", "Glossy Indirect"),
    ("use_pass_transmission_direct", "Transmission Direct"),
    ("use_pass_transmission_indirect", "Transmission Indirect"),
    ("use_pass_environment", "Environment"),
    ("use_pass_ambient_occlusion", "Ambient Occlusion"),
    ("use_pass_shadow", "Shadow"),
)
# The same under view_layer.cycles (present while the Cycles add-on is enabled).
_UNSUPPORTED_CYCLES_TOGGLES = (
    ("use_pass_volume_direct", "Volume Direct"),
    ("use_pass_volume_indirect", "Volume Indirect"),
    ("use_pass_shadow_catcher", "Shadow Catcher"),
)

# Pass type for register_pass, as Cycles registers each.
_PASS_TYPES = {"Depth": "VALUE", "Mist": "VALUE", "IndexOB": "VALUE", "IndexMA": "VALUE",
               "Normal": "VECTOR", "Position": "VECTOR", "UV": "VECTOR", "DiffCol": "COLOR",
               "GlossCol": "COLOR", "TransCol": "COLOR", "Emit": "COLOR",
               "Denoising Normal": "VECTOR", "Denoising Albedo": "COLOR",
               "Denoising Depth": "VALUE"}
# View Layer > Passes > Data > Denoising Data (Cycles' toggle, under view_layer.cycles).
DENOISING_PASSES = ("Denoising Normal", "Denoising Albedo", "Denoising Depth")

# World > Mist Pass falloff -> Cycles' exponent.
_MIST_FALLOFF = {"QUADRATIC": 2.0, "LINEAR": 1.0, "INVERSE_QUADRATIC": 0.5}


def enabled(native, view_layer):
    """[(name, channels, channel ids, bit)] of the data passes the view layer enables, in the
    native table's order."""
    names = {name for prop, name in DATA_PASS_TOGGLES if getattr(view_layer, prop, False)}
    cycles = getattr(view_layer, "cycles", None)
    if cycles is not None and getattr(cycles, "denoising_store_passes", False):
        names.update(DENOISING_PASSES)
    return [p for p in native.DATA_PASSES if p[0] in names]


def _view_layer_aovs(view_layer):
    return [aov for aov in getattr(view_layer, "aovs", ()) if aov.type in ('COLOR', 'VALUE')]


def shader_aovs(native, scene, view_layer):
    """{name: 'COLOR' | 'VALUE'} of the view layer's shader AOVs Photon writes, in its order.
    Left out, as Cycles leaves them out: those Blender marks invalid, unnamed ones, and those
    named like a pass the render writes anyway (Blender checks that only when the list is edited in its UI,
    so a script can add an AOV called Mist beside the Mist pass)."""
    return dict(settings(native, scene, view_layer).aovs)


def skipped_aovs(native, scene, view_layer):
    """Names of the view layer's shader AOVs that shader_aovs leaves out."""
    written = shader_aovs(native, scene, view_layer)
    return [aov.name for aov in _view_layer_aovs(view_layer) if aov.name not in written]


def cryptomatte_bits(native, view_layer):
    """The native CRYPTOMATTE_* bits of the Cryptomatte passes the view layer enables."""
    bits = 0
    for kind, (_pass, prop) in zip(("OBJECT", "MATERIAL", "ASSET"), cryptomatte.KINDS):
        if getattr(view_layer, prop, False):
            bits |= getattr(native, f"CRYPTOMATTE_{kind}")
    return bits


def register(engine, native, scene, view_layer):
    """Registers the enabled data and Cryptomatte passes (the compositor's Render Layers node
    shows them)."""
    out = settings(native, scene, view_layer)
    value_aovs = {name for name, kind in out.aovs if kind == 'VALUE'}
    for name, channels, chan_id in native.data_pass_names(out):
        # AOVs never share a pass's name (settings leaves such AOVs out).
        pass_type = _PASS_TYPES.get(name, "VALUE" if name in value_aovs else "COLOR")
        engine.register_pass(scene, view_layer, name, channels, chan_id, pass_type)


def settings(native, scene, view_layer, origin=None):
    """The native DataPassSettings for the view layer's passes and the scene's world mist."""
    out = native.DataPassSettings()
    mask = 0
    for _name, _channels, _chan_id, bit in enabled(native, view_layer):
        mask |= bit
    out.mask = mask
    out.cryptomatte = cryptomatte_bits(native, view_layer)
    out.cryptomatte_depth = int(getattr(view_layer, "pass_cryptomatte_depth", 6))
    out.cryptomatte_default_material = cryptomatte.name_id(cryptomatte.DEFAULT_MATERIAL)
    out.alpha_threshold = float(getattr(view_layer, "pass_alpha_threshold", 0.5))
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
    # Every light pass name counts, enabled or not (properties.py would import back into sync).
    taken = {"Combined", *getattr(native, "PASS_NAMES", ())}
    taken.update(name for name, _channels, _ids in native.data_pass_names(out))
    out.aovs = [(aov.name, aov.type) for aov in _view_layer_aovs(view_layer)
                if aov.name and getattr(aov, "is_valid", True) and aov.name not in taken]
    return out


def unsupported(view_layer, skipped_aov_names=()):
    """Labels of the passes the view layer enables that Photon does not render (they are not
    registered, so the result has none of them), light groups and `skipped_aov_names`
    (skipped_aovs) included."""
    labels = [label for prop, label in _UNSUPPORTED_TOGGLES if getattr(view_layer, prop, False)]
    cycles = getattr(view_layer, "cycles", None)
    if cycles is not None:
        labels += [label for prop, label in _UNSUPPORTED_CYCLES_TOGGLES
                   if getattr(cycles, prop, False)]
    labels += [f"AOV '{name}' (its name is empty or another pass's)"
               for name in skipped_aov_names]
    labels += [f"Light Group '{group.name}'" for group in getattr(view_layer, "lightgroups", ())]
    return labels


def warn_unsupported(reporter, native, scene, view_layer):
    """One warning naming every enabled pass Photon does not render."""
    labels = unsupported(view_layer, skipped_aovs(native, scene, view_layer))
    if labels:
        reporter.warning(f"passes not rendered by Photon (View Layer > Passes), left out of "
                         f"the result: {', '.join(labels)}")
