"""Cryptomatte Object, Material and Asset passes from Photon work as Cycles' do: the same pass
names and layers, the same metadata (layer names, hashing, manifests with the same IDs), the
same coverage per ID, and Blender's Cryptomatte node keys an object out of Photon's render as
it does out of Cycles' (scripts/cryptomatte_scene.py)."""

import json
from pathlib import Path

import numpy as np
import OpenImageIO as oiio
import pytest

SCENE = Path(__file__).resolve().parent / "scripts" / "cryptomatte_scene.py"
KINDS = ("CryptoObject", "CryptoMaterial", "CryptoAsset")
LAYERS = 3  # Levels 6: two ranks per RGBA layer


def render(blender, out_prefix, engine):
    args = ["-o", f"{out_prefix}####", "-F", "OPEN_EXR_MULTILAYER", "--python", str(SCENE),
            "-f", "1", "--", engine]
    proc = blender.run(args, timeout=300)
    if engine == "PHOTON":
        assert "Photon: rendered frame 1" in proc.stdout, f"Photon did not render\n{proc.log}"
    return proc


def read_exr(path):
    """({'Layer.Pass': (H, W, channels)}, {metadata key: value}) of a multilayer EXR."""
    buf = oiio.ImageBuf(str(path))
    spec = buf.spec()
    pixels = np.asarray(buf.get_pixels(oiio.FLOAT))
    passes = {}
    for index, name in enumerate(spec.channelnames):
        layer, render_pass, _channel = name.rsplit(".", 2)
        passes.setdefault(f"{layer}.{render_pass}", []).append(pixels[..., index])
    metadata = {a.name: a.value for a in spec.extra_attribs if a.name.startswith("cryptomatte/")}
    return {p: np.stack(c, axis=-1) for p, c in passes.items()}, metadata


def coverage_by_id(passes, kind):
    """{ID bits: (H, W) coverage} summed over a kind's ranks."""
    out = {}
    for layer in range(LAYERS):
        rgba = passes[f"ViewLayer.{kind}{layer:02d}"]
        for rank in (0, 2):
            ids = np.ascontiguousarray(rgba[..., rank]).view(np.uint32)
            cov = rgba[..., rank + 1]
            for id_bits in np.unique(ids[cov > 0]):
                out.setdefault(int(id_bits), np.zeros(cov.shape, np.float64))
                out[int(id_bits)] += np.where(ids == id_bits, cov, 0.0)
    return out


def layer_metadata(metadata, layer_name):
    """{'name', 'hash', 'conversion', 'manifest'} of the Crypto layer called `layer_name`."""
    for key, value in metadata.items():
        if key.endswith("/name") and value == layer_name:
            prefix = key[:-len("name")]
            return {k[len(prefix):]: v for k, v in metadata.items() if k.startswith(prefix)}
    return None


@pytest.fixture(scope="module")
def renders(blender, tmp_path_factory):
    out = tmp_path_factory.mktemp("cryptomatte")
    proc = render(blender, out / "photon_", "PHOTON")
    render(blender, out / "cycles_", "CYCLES")
    return proc, read_exr(out / "photon_0001.exr"), read_exr(out / "cycles_0001.exr")


def test_passes_and_metadata_match_cycles(renders):
    proc, (photon, photon_meta), (cycles, cycles_meta) = renders
    assert "Cryptomatte" not in proc.stdout, proc.log  # no "not rendered" warning
    for kind in KINDS:
        for layer in range(LAYERS):
            name = f"ViewLayer.{kind}{layer:02d}"
            assert name in photon, f"Photon wrote no {name}: {sorted(photon)}"
            assert photon[name].shape == cycles[name].shape == (120, 160, 4)
        ours = layer_metadata(photon_meta, f"ViewLayer.{kind}")
        theirs = layer_metadata(cycles_meta, f"ViewLayer.{kind}")
        assert ours is not None, f"no {kind} metadata in Photon's EXR: {sorted(photon_meta)}"
        assert ours["hash"] == theirs["hash"] == "MurmurHash3_32"
        assert ours["conversion"] == theirs["conversion"] == "uint32_to_float32"
        ours_manifest, theirs_manifest = json.loads(ours["manifest"]), json.loads(theirs["manifest"])
        if kind == "CryptoMaterial":
            # Cycles also lists its built-in shaders (default_volume, default_light, ...).
            assert set(ours_manifest) == {"FloorMat", "Red", "Blue", "Gauze", "default_surface"}
            assert all(theirs_manifest[name] == ours_manifest[name] for name in ours_manifest)
        else:
            assert ours_manifest == theirs_manifest, kind
    assert "Rig" in json.loads(layer_metadata(photon_meta, "ViewLayer.CryptoAsset")["manifest"])


def test_coverage_matches_cycles(renders):
    _proc, (photon, photon_meta), (cycles, _meta) = renders
    for kind in KINDS:
        ours, theirs = coverage_by_id(photon, kind), coverage_by_id(cycles, kind)
        manifest = json.loads(layer_metadata(photon_meta, f"ViewLayer.{kind}")["manifest"])
        names = {int(h, 16): n for n, h in manifest.items()}
        assert set(ours) == set(theirs) & set(names) | set(ours), kind
        for id_bits, cov in theirs.items():
            name = names.get(id_bits, f"{id_bits:08x}")
            mine = ours.get(id_bits)
            assert mine is not None, f"{kind}: Photon never saw {name}"
            # The share of the frame each ID covers: equal within Cycles' noise at 16 samples.
            assert abs(mine.mean() - cov.mean()) < 0.004, (
                f"{kind} {name}: Photon covers {mine.mean():.4f}, Cycles {cov.mean():.4f}")
        # Where one ID clearly owns a pixel in both engines, it is the same ID.
        top_ours = photon[f"ViewLayer.{kind}00"]
        top_theirs = cycles[f"ViewLayer.{kind}00"]
        clear = (top_ours[..., 1] > 0.9) & (top_theirs[..., 1] > 0.9)
        assert clear.mean() > 0.6  # the rest: the sky (no ID), edges and the veil
        same = (np.ascontiguousarray(top_ours[..., 0]).view(np.uint32)
                == np.ascontiguousarray(top_theirs[..., 0]).view(np.uint32))
        assert same[clear].mean() > 0.995, f"{kind}: {1 - same[clear].mean():.2%} differ"


def test_transparent_veil_shares_its_pixels(renders):
    """The 50% transparent veil takes half of each sample and the ball behind it the other
    half (Cycles: the path throughput times one minus the transparency)."""
    _proc, (photon, photon_meta), (cycles, _meta) = renders
    manifest = json.loads(layer_metadata(photon_meta, "ViewLayer.CryptoObject")["manifest"])
    veil, ball = int(manifest["Veil"], 16), int(manifest["Ball"], 16)
    ours, theirs = coverage_by_id(photon, "CryptoObject"), coverage_by_id(cycles, "CryptoObject")
    # Pixels whose every sample passes the veil and ends on the ball (the veil's and the
    # ball's shares add up to the whole pixel, the veil's is the half every sample gives it).
    behind = (np.isclose(ours[veil] + ours[ball], 1.0, atol=1e-5)
              & np.isclose(ours[veil], 0.5, atol=1e-6))
    assert behind.sum() > 100, "the veil does not cover the ball"
    assert np.allclose(ours[ball][behind], 0.5, atol=1e-6)
    assert abs(theirs[veil][behind].mean() - 0.5) < 0.02
    assert abs(theirs[ball][behind].mean() - 0.5) < 0.03


def test_cryptomatte_node_keys_out_the_ball(renders):
    """Blender's Cryptomatte node, keyed by the name 'Ball', finds it through Photon's
    metadata and passes: its matte equals the one it makes from Cycles' render."""
    _proc, (photon, _m), (cycles, _c) = renders
    ours = photon["Composite.Combined"][..., 0]
    theirs = cycles["Composite.Combined"][..., 0]
    assert theirs.mean() > 0.03, "the node keyed nothing out of Cycles' render"
    assert abs(ours.mean() - theirs.mean()) < 0.02 * theirs.mean()
    assert np.abs(ours - theirs).mean() < 0.005
