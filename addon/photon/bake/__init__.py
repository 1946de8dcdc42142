"""Lighting bakes: job.py syncs the scene and runs one native BakeSession over every point to
shade, targets.py lists those points (face corners, lightmap texels) and writes results back,
operators.py is the UI (operator, panel), viewport.py shows baked lighting in the viewport."""
