#include "stats_bindings.h"

#include <pybind11/stl.h>

#include "photon/session/render_session.h"

namespace py = pybind11;
using namespace photon;

namespace photon_python {

BakeStats bake_stats(const BakeResult& r) {
  return {r.build_seconds, r.prepare_seconds, r.bake_seconds,    r.locate_seconds,
          r.share_seconds, r.threads,         r.integrator_stats};
}

void register_stats_classes(py::module_& m) {
  py::class_<PhotonMapStats>(m, "PhotonMapStats", "Photon tracing and the photon maps.")
      .def_readonly("photons_emitted", &PhotonMapStats::photons_emitted)
      .def_readonly("caustic_photons_emitted", &PhotonMapStats::caustic_photons_emitted)
      .def_readonly("global_photons_stored", &PhotonMapStats::global_photons_stored)
      .def_readonly("caustic_photons_stored", &PhotonMapStats::caustic_photons_stored)
      .def_readonly("radiance_points", &PhotonMapStats::radiance_points)
      .def_readonly("photon_rays", &PhotonMapStats::photon_rays)
      .def_readonly("photon_map_bytes", &PhotonMapStats::photon_map_bytes)
      .def_readonly("radiance_cell_size", &PhotonMapStats::radiance_cell_size)
      .def_readonly("global_gather_radius", &PhotonMapStats::global_gather_radius)
      .def_readonly("caustic_gather_radius", &PhotonMapStats::caustic_gather_radius)
      .def_readonly("photon_trace_seconds", &PhotonMapStats::photon_trace_seconds)
      .def_readonly("photon_map_build_seconds", &PhotonMapStats::photon_map_build_seconds)
      .def_readonly("radiance_precompute_seconds", &PhotonMapStats::radiance_precompute_seconds);
  py::class_<PhotonMemoryStats>(m, "PhotonMemoryStats", "The photon memory plan.")
      .def_readonly("estimate_bytes", &PhotonMemoryStats::estimate_bytes)
      .def_readonly("available_bytes", &PhotonMemoryStats::available_bytes);
  py::class_<IrradianceCacheStats>(m, "IrradianceCacheStats", "An irradiance cache's build.")
      .def_readonly("records", &IrradianceCacheStats::records)
      .def_readonly("candidates", &IrradianceCacheStats::candidates)
      .def_readonly("gather_rays", &IrradianceCacheStats::gather_rays)
      .def_readonly("bytes", &IrradianceCacheStats::bytes)
      .def_readonly("seconds", &IrradianceCacheStats::seconds);
  py::class_<RadiosityStats>(m, "RadiosityStats", "Radiosity meshing and solve.")
      .def_readonly("elements", &RadiosityStats::elements)
      .def_readonly("patches", &RadiosityStats::patches)
      .def_readonly("clusters", &RadiosityStats::clusters)
      .def_readonly("split_patches", &RadiosityStats::split_patches)
      .def_readonly("first_patches", &RadiosityStats::first_patches)
      .def_readonly("vertices", &RadiosityStats::vertices)
      .def_readonly("patch_size", &RadiosityStats::patch_size)
      .def_readonly("area", &RadiosityStats::area)
      .def_readonly("rays", &RadiosityStats::rays)
      .def_readonly("rays_per_second", &RadiosityStats::rays_per_second)
      .def_readonly("shooting_iterations", &RadiosityStats::shooting_iterations)
      .def_readonly("averaged_iterations", &RadiosityStats::averaged_iterations)
      .def_readonly("emitted_power", &RadiosityStats::emitted_power)
      .def_readonly("absorbed_power", &RadiosityStats::absorbed_power)
      .def_readonly("absorbed_specular_power", &RadiosityStats::absorbed_specular_power)
      .def_readonly("escaped_power", &RadiosityStats::escaped_power)
      .def_readonly("unshot_power", &RadiosityStats::unshot_power)
      .def_readonly("mesh_seconds", &RadiosityStats::mesh_seconds)
      .def_readonly("solve_seconds", &RadiosityStats::solve_seconds)
      .def_readonly("field_seconds", &RadiosityStats::field_seconds);
  py::class_<PrepareStats>(m, "PrepareStats",
                           "What the integrator's preparation did; a group is None when its "
                           "stage did not run.")
      .def_readonly("photon_map", &PrepareStats::photon_map)
      .def_readonly("photon_memory", &PrepareStats::photon_memory)
      .def_readonly("irradiance_cache", &PrepareStats::irradiance_cache)
      .def_readonly("bake_irradiance_cache", &PrepareStats::bake_irradiance_cache)
      .def_readonly("radiosity", &PrepareStats::radiosity);
  py::class_<PreparedStateStats>(m, "PreparedStateStats",
                                 "A prepared-state file a render loaded or saved.")
      .def_readonly("loaded", &PreparedStateStats::loaded)
      .def_readonly("saved", &PreparedStateStats::saved)
      .def_readonly("bytes", &PreparedStateStats::bytes)
      .def_readonly("load_seconds", &PreparedStateStats::load_seconds)
      .def_readonly("save_seconds", &PreparedStateStats::save_seconds)
      .def_readonly("fingerprint", &PreparedStateStats::fingerprint);
  py::class_<RenderStats>(m, "RenderStats", "A render's statistics (RenderSession.stats).")
      .def_readonly("texture_seconds", &RenderStats::texture_seconds)
      .def_readonly("textures", &RenderStats::textures)
      .def_readonly("textures_reused", &RenderStats::textures_reused)
      .def_readonly("build_seconds", &RenderStats::build_seconds)
      .def_readonly("prepare_seconds", &RenderStats::prepare_seconds)
      .def_readonly("render_seconds", &RenderStats::render_seconds)
      .def_readonly("camera_samples", &RenderStats::camera_samples)
      .def_readonly("non_finite_samples", &RenderStats::non_finite_samples)
      .def_readonly("unique_triangles", &RenderStats::unique_triangles)
      .def_readonly("instances", &RenderStats::instances)
      .def_readonly("bvh_count", &RenderStats::bvh_count)
      .def_readonly("bvh_reused", &RenderStats::bvh_reused)
      .def_readonly("lights", &RenderStats::lights)
      .def_readonly("threads", &RenderStats::threads)
      .def_readonly("integrator", &RenderStats::integrator)
      .def_readonly("prepared_state", &RenderStats::prepared_state)
      .def_readonly("iterations", &RenderStats::iterations);
  py::class_<BakeStats>(m, "BakeStats", "A bake's statistics (the result's 'stats').")
      .def_readonly("build_seconds", &BakeStats::build_seconds)
      .def_readonly("prepare_seconds", &BakeStats::prepare_seconds)
      .def_readonly("bake_seconds", &BakeStats::bake_seconds)
      .def_readonly("locate_seconds", &BakeStats::locate_seconds)
      .def_readonly("share_seconds", &BakeStats::share_seconds)
      .def_readonly("threads", &BakeStats::threads)
      .def_readonly("integrator", &BakeStats::integrator);
}

}  // namespace photon_python
