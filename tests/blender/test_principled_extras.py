"""Principled sheen, anisotropic specular, transmission roughness and subsurface fallback, the
Diffuse BSDF's Oren-Nayar roughness, the Velvet BSDF and the Beckmann distribution, against
Cycles: a sphere per feature under a sun and a grey world, rendered by both engines in one
Blender run; the sphere's mean colour must agree within 2% (of its brightest channel)."""

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402

TOLERANCE = 0.02
RES = 64
ORTHO_SCALE = 2.2
FEATURES = ["sheen", "anisotropic", "transmission_roughness", "subsurface", "oren_nayar", "velvet",
            "beckmann_glossy", "beckmann_anisotropic"]
# Tighter where the 2% would not tell the feature from what it replaced: the Beckmann Glossy
# sphere rendered as GGX comes out 0.9% darker than Cycles' (0.03% as Beckmann, Blender 3.4).
# The anisotropic one as GGX is 7.7% darker; as Beckmann Cycles 3.4 is 1.7% brighter, all of it
# in the grey world's light found by BSDF sampling (under the sun alone the two agree to
# 0.07%): Cycles 3.4 samples anisotropic Beckmann normals with three Newton steps of fast
# erf approximations, where Photon's sampling is checked against its density (chi-square).
TOLERANCES = {"beckmann_glossy": 0.005}


def sphere_mask():
    """Pixels well inside the sphere's disc (radius 1 seen through the orthographic camera)."""
    yy, xx = np.mgrid[0:RES, 0:RES] + 0.5
    radius = RES / 2 * 2.0 / ORTHO_SCALE
    return (xx - RES / 2) ** 2 + (yy - RES / 2) ** 2 <= (0.97 * radius) ** 2


@pytest.fixture(scope="module")
def renders(blender, tmp_path_factory):
    folder = tmp_path_factory.mktemp("principled_extras")
    result, proc = blender.run_script("principled_extras.py", folder, 256, 512, "all",
                                      timeout=900)
    assert "exception" not in result, result.get("exception")
    result["log"] = proc.stdout
    return result


@pytest.mark.parametrize("feature", FEATURES)
def test_sphere_mean_matches_cycles(renders, feature):
    if feature in renders["skipped"]:
        pytest.skip(renders["skipped"][feature])
    paths = renders[feature]
    ours = read_image(paths["photon"])[..., :3]
    theirs = read_image(paths["cycles"])[..., :3]
    mask = sphere_mask()
    mean_ours, mean_theirs = ours[mask].mean(axis=0), theirs[mask].mean(axis=0)
    rel = (mean_ours - mean_theirs) / max(mean_theirs.max(), 1e-6)
    print(f"{feature:24s} photon {np.round(mean_ours, 4)} cycles {np.round(mean_theirs, 4)} "
          f"rel {np.round(rel, 4)}")
    assert np.abs(rel).max() <= TOLERANCES.get(feature, TOLERANCE), (
        feature, mean_ours, mean_theirs, rel)


def test_only_the_subsurface_fallback_is_reported(blender, renders):
    if "subsurface" in renders["skipped"]:
        pytest.skip(renders["skipped"]["subsurface"])
    log = renders["log"]
    assert "Photon: rendered frame" in log
    # Only the subsurface radius (which the diffuse fallback has no use for) is listed as
    # ignored; sheen, anisotropy and transmission roughness render. Principled v2 lists the
    # Subsurface inputs only when linked.
    warnings = [line for line in log.splitlines() if line.startswith("Photon: warning:")]
    ignored = [line for line in warnings if "rendered at their defaults" in line]
    assert ignored == ([] if blender.version >= (4, 0) else [
        "Photon: warning: Material 'subsurface': Principled BSDF inputs not supported yet are "
        "rendered at their defaults: Subsurface Radius"]), log
    fallback = [line for line in warnings if "subsurface scattering is not supported" in line]
    assert len(fallback) == 1, log


def test_clearcoat_normal_and_anisotropic_bsdf_convert(blender):
    result, proc = blender.run_script("principled_extras_closures.py")
    assert "exception" not in result, result.get("exception")
    coat = result["Coat"]
    (closure,) = coat["closures"]
    # The bumped Clearcoat Normal is a program register; the base normal stays unlinked.
    assert coat["program"] and isinstance(closure["clearcoat_normal"]["register"], int)
    assert "normal" not in closure and coat["warnings"] == []
    brushed = result["Brushed"]
    (closure,) = brushed["closures"]
    assert closure["type"] == "ANISOTROPIC"
    assert abs(closure["params"]["anisotropic"] + 0.4) < 1e-6
    assert abs(closure["params"]["anisotropic_rotation"] - 0.2) < 1e-6
    # Blender 4.0 merged the Anisotropic BSDF into the Glossy BSDF (the node's name with it).
    node = "Anisotropic BSDF" if blender.version < (4, 0) else "Glossy BSDF"
    assert brushed["warnings"] == [f"Material 'Brushed': node '{node}': a linked Tangent is not "
                                   "supported; using the UV map's tangent"]
