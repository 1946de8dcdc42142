"""Cryptomatte IDs and metadata as the Cryptomatte 1.2 specification (Psyop) and Blender's
Cycles write them: a name's ID is MurmurHash3_x86_32 of its UTF-8 bytes (seed 0), stored in a
float channel as the same 32 bits, the exponent nudged off 0 and 255 so the float is never
denormal, infinite or NaN; each Crypto layer's EXR metadata lives under
cryptomatte/<first 7 hex digits of the layer name's hash>/ with its name, hash and conversion
and a manifest mapping every name to its 8-hex-digit ID."""

import json
import struct

# Blender's pass and layer names per kind, and the view-layer flag that enables it.
KINDS = (
    ("CryptoObject", "use_pass_cryptomatte_object"),
    ("CryptoMaterial", "use_pass_cryptomatte_material"),
    ("CryptoAsset", "use_pass_cryptomatte_asset"),
)


def _rotl32(x, r):
    return ((x << r) | (x >> (32 - r))) & 0xFFFFFFFF


def murmur3_32(data, seed=0):
    """MurmurHash3_x86_32 (Austin Appleby, public domain algorithm) of `data` (bytes)."""
    c1, c2 = 0xCC9E2D51, 0x1B873593
    h = seed & 0xFFFFFFFF
    n_blocks = len(data) // 4
    for (k,) in struct.iter_unpack("<I", data[:n_blocks * 4]):
        k = _rotl32((k * c1) & 0xFFFFFFFF, 15) * c2 & 0xFFFFFFFF
        h = (_rotl32(h ^ k, 13) * 5 + 0xE6546B64) & 0xFFFFFFFF
    tail = data[n_blocks * 4:]
    k = 0
    for i, byte in enumerate(tail):
        k |= byte << (8 * i)
    if tail:
        h ^= _rotl32((k * c1) & 0xFFFFFFFF, 15) * c2 & 0xFFFFFFFF
    h ^= len(data)
    h ^= h >> 16
    h = (h * 0x85EBCA6B) & 0xFFFFFFFF
    h ^= h >> 13
    h = (h * 0xC2B2AE35) & 0xFFFFFFFF
    return h ^ (h >> 16)


# The name Cycles gives the surface shader of objects without a material.
DEFAULT_MATERIAL = "default_surface"


def name_hash(name):
    return murmur3_32(name.encode("utf-8"))


def name_id(name):
    """The float a pass stores for `name`."""
    return hash_to_float(name_hash(name))


def hash_to_float(h):
    """The ID as stored in a pass: the hash's bits as a float32, its exponent moved off 0 and
    255 (spec: 'uint32_to_float32')."""
    exponent = (h >> 23) & 0xFF
    if exponent in (0, 255):
        h ^= 1 << 23
    return struct.unpack("<f", struct.pack("<I", h))[0]


def manifest(names):
    """The manifest JSON: every name with its ID as 8 hex digits, in the order given."""
    return json.dumps({name: f"{name_hash(name):08x}" for name in names},
                      separators=(",", ":"), ensure_ascii=False)


class Names:
    """The names of what a sync put into the scene, per Cryptomatte kind, each made into its
    ID once (a scene of many instances of a few objects hashes each name once)."""

    def __init__(self, bits_enabled):
        self.enabled = bits_enabled  # {"CryptoObject": bool, ...}
        self.names = {kind: {} for kind, _prop in KINDS}  # kind -> {name: id}, in first-seen order

    @classmethod
    def for_view_layer(cls, view_layer):
        return cls({kind: bool(getattr(view_layer, prop, False)) for kind, prop in KINDS})

    def any(self):
        return any(self.enabled.values())

    def id(self, kind, name):
        ids = self.names[kind]
        found = ids.get(name)
        if found is None:
            found = ids[name] = name_id(name)
        return found

    def layer_metadata(self, view_layer_name):
        """(key, value) pairs of the result's metadata for every enabled kind."""
        pairs = []
        for kind, _prop in KINDS:
            if self.enabled[kind]:
                pairs += metadata(f"{view_layer_name}.{kind}", list(self.names[kind]))
        return pairs


def asset_name(obj):
    """Cycles' Cryptomatte asset: the name of the top of the object's parent chain (its own
    name without a parent)."""
    while obj.parent is not None:
        obj = obj.parent
    return obj.name


def metadata(layer_name, names):
    """(key, value) pairs of the render result's metadata for one Crypto layer
    ('ViewLayer.CryptoObject')."""
    prefix = f"cryptomatte/{name_hash(layer_name):08x}"[:len("cryptomatte/") + 7] + "/"
    return [(prefix + "name", layer_name), (prefix + "hash", "MurmurHash3_32"),
            (prefix + "conversion", "uint32_to_float32"), (prefix + "manifest", manifest(names))]
