"""IES Texture nodes in a light's node tree: the profile text and strength add_light takes.

Cycles multiplies the Emission node's Strength by the IES node's Fac, its Strength times the
profile along the direction leaving the lamp. Photon reads that when the Emission Strength is fed
by the IES node directly, or through a Math Multiply by a value; the native library reads the
LM-63 text (lights/ies_profile.h)."""

import os

import bpy

from . import nodes

# No photometric file is this large; a bigger one is not read into memory.
MAX_IES_BYTES = 16 * 1024 * 1024


def _label(node):
    return f"{node.bl_label} '{node.name}'" if node.name != node.bl_label else node.bl_label


def _read_file(node):
    """(text, source) of an IES node in File mode: the text is "" when it cannot be read, and
    the source then says why."""
    raw = getattr(node, "filepath", "") or ""
    if not raw:
        return "", "no file chosen"
    library = getattr(node.id_data, "library", None)
    path = bpy.path.abspath(raw, library=library)
    try:
        size = os.path.getsize(path)
        if size > MAX_IES_BYTES:
            return "", f"{path}: {size / 2**20:.0f} MiB, more than an IES file holds"
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        return "", f"{path}: {e.strerror or e}"
    # LM-63 is ASCII; stray bytes of other encodings are only ever in its keyword lines.
    return data.decode("latin-1"), path


def _read_text(node):
    """(text, source) of an IES node in Internal mode (a text datablock)."""
    text = getattr(node, "ies", None)
    if text is None:
        return "", "no text chosen"
    return text.as_string(), f"text '{text.name}'"


def _multiplier(node, ies_output):
    """The constant a Math Multiply node scales `ies_output` by, or None when `node` is not
    such a node."""
    if node.type != 'MATH' or node.operation != 'MULTIPLY' or getattr(node, "use_clamp", False):
        return None
    first, second = node.inputs[0], node.inputs[1]
    for this, other in ((first, second), (second, first)):
        found = nodes.source(this)
        if found.node is not None and found.socket == ies_output and not other.is_linked:
            return float(other.default_value)
    return None


def strength_profile(strength_socket, name, reporter):
    """The IES profile feeding a light's Emission Strength as add_light's keyword arguments
    (ies, ies_strength, ies_source), or None when no IES node feeds it the way Photon reads."""
    found = nodes.source(strength_socket)
    node, factor = found.node, 1.0
    if node is None:
        return None
    if node.type == 'MATH':
        upstream = [nodes.source(s).node for s in node.inputs[:2]]
        ies_nodes = [n for n in upstream if n is not None and n.type == 'TEX_IES']
        if not ies_nodes:
            return None
        factor = _multiplier(node, ies_nodes[0].outputs[0])
        if factor is None:
            return None
        node = ies_nodes[0]
    if node.type != 'TEX_IES':
        return None
    if node.mode == 'EXTERNAL':
        text, source = _read_file(node)
    else:
        text, source = _read_text(node)
    vector = nodes.find_input(node, "Vector")
    if vector is not None and vector.is_linked:
        reporter.warning(f"Light '{name}': the Vector of its {_label(node)} is linked, which "
                         f"Photon does not evaluate; the profile is read along the direction "
                         f"leaving the lamp, the node's default")
    strength = nodes.find_input(node, "Strength")
    value = 1.0
    if strength is not None:
        if strength.is_linked:
            reporter.warning(f"Light '{name}': the Strength of its {_label(node)} is linked, "
                             f"which Photon does not evaluate; its own value is used")
        value = float(strength.default_value)
    return {"ies": text, "ies_strength": value * factor, "ies_source": source,
            "ies_edges": cycles_ies_edges(), "ies_area_by_direction": bpy.app.version >= (4, 0, 0)}


def cycles_ies_edges():
    """How this Blender's Cycles interpolates past a profile table's edges (IesEdges): it
    changed in 4.1 (zero outside) and again in 5.1 (the edge row repeated)."""
    if bpy.app.version < (4, 1, 0):
        return "CLAMP"
    return "ZERO" if bpy.app.version < (5, 1, 0) else "HOLD"
