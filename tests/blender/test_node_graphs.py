"""Shader graphs that share sub-trees or run long (addon/photon/sync/graph.py): they convert and
render in bounded time, paths to one closure add up, and the closure count is capped with a
warning. The graphs are built by scripts/node_graphs.py (see its docstring)."""

import re
import subprocess
import sys
from collections import Counter
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402

TIMEOUT = 60  # seconds for one conversion or render (each well under 10 s when linear)
MAX_CLOSURES = 64


def run_bounded(what, call):
    try:
        return call()
    except subprocess.TimeoutExpired:
        pytest.fail(f"{what} did not finish in {TIMEOUT} s")


def convert(blender, kind, size):
    result, _ = run_bounded(f"converting {kind} {size}", lambda: blender.run_script(
        "node_graphs.py", "convert", kind, size, timeout=TIMEOUT))
    assert "exception" not in result, result["exception"]
    return result


def constant_weight(closure):
    """The weight of a closure whose factors are all constants."""
    weight = 1.0
    for factor in closure["weight"]:
        assert isinstance(factor["fac"], float), closure["weight"]
        weight *= 1.0 - factor["fac"] if factor["complement"] else factor["fac"]
    return weight


def glossy_closure(blender):
    """The closure a Glossy BSDF node makes: from Blender 4.0 the node is the merged
    Glossy/Anisotropic one, read as anisotropic GGX (isotropic at Anisotropy 0)."""
    return "ANISOTROPIC" if blender.version >= (4, 0) else "GLOSSY"


def diamond_weights(facs, glossy, textured_level=None):
    """{(leaf, texture factor): weight} of the diamond's output A_N, by the Mix Shader's
    definition (1 - fac) * first + fac * second applied level by level. The texture factor is
    None, "t" or "1-t" (the textured level's Alpha); `glossy` names the glossy leaf's closure."""
    a = {("DIFFUSE", None): 1.0}
    b = {(glossy, None): 1.0}
    for level, (fa, fb) in enumerate(facs, start=1):
        def mix(fac, first, second):
            out = Counter()
            for inputs, w_const, tex in ((first, 1.0 - fac, "1-t"), (second, fac, "t")):
                for (leaf, factor), weight in inputs.items():
                    if level == textured_level:
                        out[(leaf, tex)] += weight
                    else:
                        out[(leaf, factor)] += weight * w_const
            return out
        a, b = mix(fa, a, b), mix(fb, b, a)
    return dict(a)


@pytest.mark.parametrize("depth", [10, 20])
def test_constant_diamond_collapses_to_its_leaves_with_summed_weights(blender, depth):
    result = convert(blender, "diamond", depth)
    closures = result["closures"]
    glossy = glossy_closure(blender)
    assert [c["type"] for c in closures] == ["DIFFUSE", glossy]
    expected = diamond_weights(result["facs"], glossy)
    assert constant_weight(closures[0]) == pytest.approx(expected[("DIFFUSE", None)], rel=1e-9)
    assert constant_weight(closures[1]) == pytest.approx(expected[(glossy, None)], rel=1e-9)
    assert sum(constant_weight(c) for c in closures) == pytest.approx(1.0, rel=1e-9)
    assert np.allclose(closures[0]["params"]["color"], [0.8, 0.2, 0.1])
    assert closures[1]["params"]["roughness"] == pytest.approx(0.4)
    assert result["warnings"] == []
    print(f"diamond {depth}: converted in {result['seconds']:.4f} s")


def test_textured_diamond_keeps_distinct_texture_products_apart(blender):
    result = convert(blender, "tex_diamond", 6)
    closures = result["closures"]
    # One Alpha texture at one level: each leaf has a "t" and a "1-t" entry whose constant is
    # the sum over the 2^5 constant paths around it.
    expected = diamond_weights(result["facs"], glossy_closure(blender),
                               result["textured_level"])
    assert len(expected) == 4
    got = {}
    for closure in closures:
        texture = [f for f in closure["weight"] if isinstance(f["fac"], dict)]
        assert len(texture) == 1, closure["weight"]
        assert texture[0]["fac"] == {"texture": 0, "channel": "ALPHA"}
        key = (closure["type"], "1-t" if texture[0]["complement"] else "t")
        assert key not in got, key
        got[key] = constant_weight({"weight": [f for f in closure["weight"] if f not in texture]})
    assert got.keys() == expected.keys()
    for key, weight in expected.items():
        assert got[key] == pytest.approx(weight, rel=1e-9), key


# The native BSDF holds 8 lobes per point (keeping the strongest); more closures say so.
LOBE_WARNING = ("Material '{}': 64 BSDF closures; Photon shades the 8 strongest lobes at each "
                "point and drops the rest")


def test_many_texture_products_are_capped_with_one_warning(blender):
    result = convert(blender, "tex_diamonds", 10)  # 2^10 different products of 10 textures
    closures = result["closures"]
    assert len(closures) == MAX_CLOSURES
    assert all(len(c["weight"]) == 10 for c in closures)
    assert len(result["warnings"]) == 2, result["warnings"]
    assert result["warnings"][1] == LOBE_WARNING.format("TexsDiamond10")
    assert re.fullmatch(r"Material 'TexsDiamond10': its shader mixes make at least \d+ closures; "
                        r"rendering the 64 with the largest mix weights and dropping at least "
                        r"\d+ \(Cycles' limit is 64 too\)", result["warnings"][0])


def test_long_add_chain_keeps_every_closure_in_order(blender):
    result = convert(blender, "chain", 40)
    closures = result["closures"]
    assert len(closures) == 40 and all(c["type"] == "EMISSION" for c in closures)
    assert all(c["weight"] == [] for c in closures)
    assert [c["params"]["strength"] for c in closures] == pytest.approx(result["strengths"])
    assert result["warnings"] == []


def test_wide_add_chain_keeps_the_closures_of_largest_weight_and_warns(blender):
    result = convert(blender, "add_chain", 2000)
    closures = result["closures"]
    assert len(closures) == MAX_CLOSURES
    assert result["warnings"] == [
        "Material 'AddChain2000': its shader mixes make 2000 closures; rendering the 64 with "
        "the largest mix weights and dropping 1936 (Cycles' limit is 64 too)",
        LOBE_WARNING.format("AddChain2000")]
    kept = sorted((constant_weight(c) for c in closures), reverse=True)
    largest = sorted(result["weights"], reverse=True)[:MAX_CLOSURES]
    assert kept == pytest.approx(largest, rel=1e-9)
    assert len(set(kept)) == 2  # the 50 of the weight-1 group and 14 of the next one
    print(f"add chain 2000: converted in {result['seconds']:.3f} s")


@pytest.mark.parametrize("kind, size", [("diamond", 10), ("diamond", 20), ("add_chain", 2000),
                                        ("chain", 40)])
def test_large_graphs_render_in_bounded_time(blender, tmp_path, kind, size):
    blend = tmp_path / f"{kind}{size}.blend"
    blender.run_script("node_graphs.py", "scene", kind, size, blend, timeout=TIMEOUT)
    proc = run_bounded(f"rendering {kind} {size}", lambda: blender.run(
        [str(blend), "-E", "PHOTON", "-o", str(tmp_path / "out_####"), "-F", "OPEN_EXR",
         "-x", "1", "-f", "1"], timeout=TIMEOUT, check=False))
    assert proc.returncode == 0, proc.log
    assert "Photon: rendered frame 1" in proc.stdout, proc.log
    warnings = [line for line in proc.stdout.splitlines() if "Photon: warning: Material" in line]
    if kind == "add_chain":
        assert len(warnings) == 2 and "make 2000 closures" in warnings[0], proc.log
        assert "8 strongest lobes" in warnings[1], proc.log
    else:
        assert warnings == [], proc.log
    pixels = read_image(tmp_path / "out_0001.exr")[..., :3]
    assert np.isfinite(pixels).all() and pixels.mean() > 0.01, pixels.mean()
