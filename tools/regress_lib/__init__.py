"""Library behind tools/regress.py: render.py (scenes, sidecars, headless Blender), compare.py
(images and metrics), report.py (PNGs, report.html, report.json)."""
