"""Spectral mode in Blender: its settings (scene.photon.spectral and spectral_samples from the
native schema, material.photon.abbe_number, light.photon's spectrum and a Blackbody node on a
light) reach the native scene, and the Cornell box renders in spectral mode like in RGB mode.
About 20 s."""

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402

REPO = Path(__file__).resolve().parents[2]
CORNELL = REPO / "test_scenes" / "cornell_box.blend"


def test_spectral_settings_reach_the_native_scene(blender):
    result, proc = blender.run_script("spectral_settings.py")
    assert "exception" not in result, proc.log
    rna = result["rna"]
    assert rna["spectral"] == {"type": "BOOLEAN", "default": False}
    assert rna["spectral_samples"]["default"] == 4
    assert (rna["spectral_samples"]["min"], rna["spectral_samples"]["max"]) == (1, 4)
    abbe = rna["abbe_number"]
    assert (abbe["default"], abbe["min"], abbe["max"]) == (0.0, 0.0, 200.0)
    assert rna["spectrum"]["items"] == ["RGB", "BLACKBODY", "ILLUMINANT"]
    assert rna["spectrum"]["default"] == "RGB"
    assert rna["illuminant"]["items"] == ["D65", "A", "F2", "F7", "F11"]
    assert result["panels"] == ["PHOTON_PT_spectral", "PHOTON_PT_material"]

    closures = result["closures"]
    assert [c.get("abbe") for c in closures["Glass"]] == [30.0]
    assert [c.get("abbe") for c in closures["Refraction"]] == [40.0]
    assert [c.get("abbe") for c in closures["Principled"]] == [20.0]
    assert [c.get("abbe") for c in closures["Diffuse"]] == [None]
    assert [c.get("abbe") for c in closures["PlainGlass"]] == [None]
    assert result["native_abbe"]["Glass"] == [30.0]
    assert result["native_abbe"]["PlainGlass"] == [0.0]
    # An Abbe number far below any material's (Cauchy's law then gave indices from -339 to
    # 1137) is clamped to rutile's, with a warning naming the material.
    assert [c.get("abbe") for c in closures["Absurd"]] == [9.0]
    assert result["native_abbe"]["Absurd"] == [9.0]
    assert result["native_abbe"]["raw_absurd"] == [9.0]
    assert [w for w in result["warnings"] if "Abbe" in w] == [
        "Material 'Absurd': Abbe number 0.001 is outside real materials' range (9 for rutile, "
        "the most dispersive, to 200); rendering 9"]

    spectra = result["spectra"]
    assert spectra["plain"] == ["RGB", 6500.0, "D65"]
    assert spectra["illuminant"] == ["ILLUMINANT", 6500.0, "F11"]
    assert spectra["blackbody_node"] == ["BLACKBODY", 2700.0, "D65"]
    assert spectra["blackbody_setting"] == ["BLACKBODY", 9000.0, "D65"]
    assert result["light_arguments"] == {"spectrum": "BLACKBODY", "temperature": 9000.0,
                                         "illuminant": "D65"}


def render_cornell(blender, out, spectral):
    expr = ("import bpy; s = bpy.context.scene; s.photon.spectral = %s; s.photon.samples = 16; "
            "s.render.resolution_x = s.render.resolution_y = 48; "
            "s.render.resolution_percentage = 100" % spectral)
    proc = blender.run([str(CORNELL), "-E", "PHOTON", "--python-expr", expr, "-o",
                        str(out / f"cornell_{spectral}_####"), "-F", "OPEN_EXR", "-x", "1",
                        "-f", "1"], timeout=300)
    assert "Photon: rendered frame" in proc.stdout, proc.log
    return read_image(out / f"cornell_{spectral}_0001.exr")[..., :3]


def test_cornell_box_renders_alike_in_spectral_mode(blender, tmp_path):
    rgb = render_cornell(blender, tmp_path, False)
    spectral = render_cornell(blender, tmp_path, True)
    assert not np.array_equal(rgb, spectral)  # spectral mode did run
    means_rgb, means_spectral = rgb.mean(axis=(0, 1)), spectral.mean(axis=(0, 1))
    # Interreflections of coloured walls differ a little (spectra multiply, RGB does not).
    np.testing.assert_allclose(means_spectral, means_rgb, rtol=0.04)
