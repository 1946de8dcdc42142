"""The info lines a final render reports once a view is rendered: the frame's summary (samples,
threads, sync, textures, BVH and render times), what the integrator prepared (photon maps,
irradiance cache, radiosity), SPPM/VCM iterations and Persistent Data reuse. Tests, render farms
and users read them: their wording is kept. The same figures go into the image's metadata, as
Cycles writes its own (metadata_fields)."""

import resource


def rendered_samples(settings, stats):
    """Camera samples per pixel the render took: Samples, fewer when Time Limit stopped it, or
    their mean over the pixels with adaptive sampling."""
    pixels = max(settings.x1 - settings.x0, 0) * max(settings.y1 - settings.y0, 0)
    if pixels and stats.camera_samples and not stats.iterations.iterations:
        return stats.camera_samples // pixels
    return settings.samples


def _samples_label(settings, stats):
    """'64 spp', '23 spp on average, adaptive' with adaptive sampling, or 'N SPPM iterations' /
    'N VCM iterations' for the iterative ones."""
    if stats.iterations.iterations:
        return f"{stats.iterations.iterations} {settings.integrator.name} iterations"
    if settings.adaptive_sampling:
        return f"{rendered_samples(settings, stats)} spp on average, adaptive"
    return f"{rendered_samples(settings, stats)} spp"


def _texture_stats(stats):
    """'textures 1.234 s (3, 2 cached), ' or '' for a scene without image textures."""
    if not stats.textures:
        return ""
    return (f"textures {stats.texture_seconds:.3f} s ({stats.textures}, "
            f"{stats.textures_reused} cached), ")


def _layer_view_label(scene, layer, view):
    """', view layer 'X', view left' when a frame has several layers or views, else ''."""
    label = ""
    if sum(1 for view_layer in scene.view_layers if view_layer.use) > 1:
        label += f", view layer '{layer}'"
    if view:
        label += f", view {view}"
    return label


def frame_line(state, scene, region_w, region_h, settings, stats, sync_stats, elapsed, layer,
               view):
    """'rendered frame 1 256x256 (64 spp, 2 threads): sync ... total 1.234 s' (`state`:
    rendered, cancelled, ...) of a RenderStats and the SyncStats of its scene."""
    return (f"{state} frame {scene.frame_current} {region_w}x{region_h} "
            f"({_samples_label(settings, stats)}, {stats.threads} threads): "
            f"sync {sync_stats.seconds:.3f} s "
            f"({sync_stats.triangles} triangles, {sync_stats.instances} instances, "
            f"{sync_stats.lights} lights), {_texture_stats(stats)}"
            f"BVH {stats.build_seconds:.3f} s, "
            f"render {stats.render_seconds:.3f} s, total {elapsed:.3f} s"
            f"{_layer_view_label(scene, layer, view)}")


def prepare_lines(prepared):
    """Report lines for a PrepareStats (photon maps, irradiance cache, radiosity): one per
    stage that ran."""
    lines = []
    pm = prepared.photon_map
    if pm is not None:
        lines.append(
            f"photons: {pm.photons_emitted:,} global and "
            f"{pm.caustic_photons_emitted:,} caustic emitted, "
            f"{pm.global_photons_stored:,} and "
            f"{pm.caustic_photons_stored:,} stored in "
            f"{pm.photon_trace_seconds:.3f} s; maps built in "
            f"{pm.photon_map_build_seconds:.3f} s, radiance precomputed in "
            f"{pm.radiance_precompute_seconds:.3f} s "
            f"({pm.photon_map_bytes / 1e6:.1f} MB)")
    cache = prepared.irradiance_cache
    if cache is not None:
        lines.append(
            f"irradiance cache: {cache.records:,} records, "
            f"{cache.gather_rays:,} gather rays in "
            f"{cache.seconds:.3f} s")
    r = prepared.radiosity
    if r is not None:
        lines.append(
            f"radiosity: {r.patches:,} patches (size {r.patch_size:.4g}, "
            f"{r.elements:,} elements, {r.clusters:,} clusters, meshed in "
            f"{r.mesh_seconds:.3f} s, displayed in {r.field_seconds:.3f} s), "
            f"{r.rays:,} rays in {r.solve_seconds:.3f} s "
            f"({r.rays_per_second / 1e6:.2f} M rays/s), "
            f"{r.shooting_iterations} shooting + "
            f"{r.averaged_iterations} averaged iterations; power: "
            f"emitted {r.emitted_power:.4g} W, absorbed "
            f"{r.absorbed_power + r.absorbed_specular_power:.4g}"
            f" W, escaped {r.escaped_power:.4g} W, unshot "
            f"{r.unshot_power:.4g} W")
    return lines


def iterations_line(integrator, it):
    """The report line of an SPPM or VCM render (RenderStats.iterations)."""
    if integrator == "VCM":
        return (f"vcm: {it.iterations} iterations, {it.photons_emitted:,} light paths in "
                f"{it.photon_seconds:.3f} s, camera passes {it.camera_seconds:.3f} s; light "
                f"vertices of one iteration {it.peak_photon_bytes / 1e6:.1f} MB at most")
    return (f"sppm: {it.iterations} iterations, {it.photons_emitted:,} photons emitted "
            f"in {it.photon_seconds:.3f} s, camera passes {it.camera_seconds:.3f} s; "
            f"{it.bytes_per_pixel} bytes per pixel, photons of one iteration "
            f"{it.peak_photon_bytes / 1e6:.1f} MB at most")


def persistent_data_line(sync_stats, stats):
    """What Persistent Data kept from earlier frames, or None when it is off."""
    if sync_stats.meshes_reused is None:
        return None
    meshes = sync_stats.meshes_reused + sync_stats.meshes_exported
    return (f"persistent data: reused {sync_stats.meshes_reused} of {meshes} "
            f"meshes, {stats.bvh_reused} of {stats.bvh_count} BVHs")


def timecode(seconds):
    """A duration as Blender writes render times into metadata (Cycles' cycles.*_time fields):
    MM:SS.cc, or HH:MM:SS.cc from an hour on."""
    centiseconds = int(round(max(float(seconds), 0.0) * 100.0))
    hours, rest = divmod(centiseconds, 360000)
    minutes, rest = divmod(rest, 6000)
    secs, hundredths = divmod(rest, 100)
    if hours:
        return f"{hours:02d}:{minutes:02d}:{secs:02d}.{hundredths:02d}"
    return f"{minutes:02d}:{secs:02d}.{hundredths:02d}"


def metadata_fields(layer, settings, stats, sync_stats, elapsed):
    """[(key, value)] of a rendered view for the render result's metadata (EXR headers, the
    Metadata panel), under photon.<view layer>. as Cycles writes cycles.<view layer>.*: the
    integrator, samples (or iterations), threads, the total, synchronization, preparation
    (BVH, textures, photon maps and caches) and render times, and the process's peak memory."""
    prefix = f"photon.{layer}."
    fields = [("integrator", settings.integrator.name),
              ("samples", str(rendered_samples(settings, stats)))]
    if stats.iterations.iterations:
        fields.append(("iterations", str(stats.iterations.iterations)))
    preparation = stats.build_seconds + stats.texture_seconds + stats.prepare_seconds
    peak_mib = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0  # kB on Linux
    fields += [("threads", str(stats.threads)),
               ("total_time", timecode(elapsed)),
               ("synchronization_time", timecode(sync_stats.seconds)),
               ("preparation_time", timecode(preparation)),
               ("render_time", timecode(stats.render_seconds)),
               ("peak_memory", f"{peak_mib:.1f}M")]
    return [(prefix + key, value) for key, value in fields]
