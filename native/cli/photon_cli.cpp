// photon_cli: renders a built-in scene without Blender, e.g.
//   photon_cli --scene cornell --width 256 --height 256 --samples 64 --out cornell.exr
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "photon/session/image_io.h"
#include "photon/session/pixel_renderer.h"
#include "photon/session/render_session.h"
#include "photon/testing/test_scenes.h"

using namespace photon;

static void usage() {
  std::printf(
      "usage: photon_cli [--scene cornell|caustic] [--width N] [--height N] [--samples N]\n"
      "                  [--max-depth N] [--seed N] [--threads N] [--tile-size N]\n"
      "                  [--integrator photon_map|ray_trace|radiosity] [--photons N]\n"
      "                  [--caustic-photons N]\n"
      "                  [--gather-count N] [--gather-radius R] [--caustic-gather-count N]\n"
      "                  [--final-gather-rays N] [--photon-time SECONDS] [--no-irradiance-cache]\n"
      "                  [--patch-size S] [--radiosity-rays N] [--radiosity-threshold F]\n"
      "                  [--radiosity-iterations N]\n"
      "                  [--passes PREFIX (writes PREFIX_direct.exr, ...)] --out FILE\n");
}

int main(int argc, char** argv) {
  RenderSettings settings;
  settings.full_width = settings.full_height = 256;
  settings.samples = 64;  // the add-on's default
  std::string scene_name = "cornell", out, passes_prefix;
  for (int i = 1; i < argc; ++i) {
    auto next = [&](const char* flag) -> const char* {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", flag);
        std::exit(2);
      }
      return argv[++i];
    };
    if (!std::strcmp(argv[i], "--scene")) scene_name = next("--scene");
    else if (!std::strcmp(argv[i], "--width")) settings.full_width = std::atoi(next("--width"));
    else if (!std::strcmp(argv[i], "--height")) settings.full_height = std::atoi(next("--height"));
    else if (!std::strcmp(argv[i], "--samples")) settings.samples = std::atoi(next("--samples"));
    else if (!std::strcmp(argv[i], "--max-depth")) settings.max_depth = std::atoi(next("--max-depth"));
    else if (!std::strcmp(argv[i], "--seed")) settings.seed = std::strtoull(next("--seed"), nullptr, 10);
    else if (!std::strcmp(argv[i], "--threads")) settings.threads = std::atoi(next("--threads"));
    else if (!std::strcmp(argv[i], "--tile-size")) settings.tile_size = std::atoi(next("--tile-size"));
    else if (!std::strcmp(argv[i], "--integrator")) {
      const std::string name = next("--integrator");
      if (name == "ray_trace") settings.integrator = IntegratorType::kRayTrace;
      else if (name == "photon_map") settings.integrator = IntegratorType::kPhotonMap;
      else if (name == "radiosity") settings.integrator = IntegratorType::kRadiosity;
      else {
        usage();
        return 2;
      }
    }
    else if (!std::strcmp(argv[i], "--photons")) settings.photons = std::strtoull(next("--photons"), nullptr, 10);
    else if (!std::strcmp(argv[i], "--caustic-photons")) settings.caustic_photons = std::strtoull(next("--caustic-photons"), nullptr, 10);
    else if (!std::strcmp(argv[i], "--gather-count")) settings.gather_count = std::atoi(next("--gather-count"));
    else if (!std::strcmp(argv[i], "--gather-radius")) settings.gather_radius = std::strtof(next("--gather-radius"), nullptr);
    else if (!std::strcmp(argv[i], "--caustic-gather-count")) settings.caustic_gather_count = std::atoi(next("--caustic-gather-count"));
    else if (!std::strcmp(argv[i], "--final-gather-rays")) settings.final_gather_rays = std::atoi(next("--final-gather-rays"));
    else if (!std::strcmp(argv[i], "--no-irradiance-cache")) settings.irradiance_cache = false;
    else if (!std::strcmp(argv[i], "--photon-time")) settings.photon_time = std::strtof(next("--photon-time"), nullptr);
    else if (!std::strcmp(argv[i], "--patch-size")) settings.radiosity_patch_size = std::strtof(next("--patch-size"), nullptr);
    else if (!std::strcmp(argv[i], "--radiosity-rays")) settings.radiosity_rays = std::strtoull(next("--radiosity-rays"), nullptr, 10);
    else if (!std::strcmp(argv[i], "--radiosity-threshold")) settings.radiosity_threshold = std::strtof(next("--radiosity-threshold"), nullptr);
    else if (!std::strcmp(argv[i], "--radiosity-iterations")) settings.radiosity_iterations = std::atoi(next("--radiosity-iterations"));
    else if (!std::strcmp(argv[i], "--passes")) {
      passes_prefix = next("--passes");
      settings.light_passes = true;
    }
    else if (!std::strcmp(argv[i], "--out")) out = next("--out");
    else {
      usage();
      return 2;
    }
  }
  if (out.empty() || (scene_name != "cornell" && scene_name != "caustic")) {
    usage();
    return 2;
  }
  settings.x1 = settings.full_width;
  settings.y1 = settings.full_height;
  auto scene = std::make_shared<Scene>(scene_name == "caustic" ? make_caustic_box() : make_cornell_box());
  const float aspect = static_cast<float>(settings.full_width) / settings.full_height;
  scene->camera.window_min_x = scene->camera.window_min_y * aspect;
  scene->camera.window_max_x = scene->camera.window_max_y * aspect;

  RenderSession session(scene, settings);
  session.start();
  std::vector<Tile> tiles;
  while (!session.finished()) {
    std::vector<Tile> batch = session.take_tiles(0.1);
    for (Tile& t : batch) tiles.push_back(std::move(t));
  }
  for (Tile& t : session.take_tiles(0.0)) tiles.push_back(std::move(t));
  session.wait();
  for (const std::string& w : session.warnings()) std::fprintf(stderr, "warning: %s\n", w.c_str());
  const RenderStats stats = session.stats();
  std::printf("rendered %dx%d, %d spp, %d threads: build %.3f s, prepare %.3f s, render %.3f s\n",
              settings.full_width, settings.full_height, settings.samples, stats.threads,
              stats.build_seconds, stats.prepare_seconds, stats.render_seconds);
  const PrepareStats& prepared = stats.integrator;
  using ull = unsigned long long;
  if (const auto& pm = prepared.photon_map)
    std::printf("  photons: %llu global and %llu caustic emitted, %llu and %llu stored in %.3f s; "
                "gather radius %g (caustic %g)\n",
                ull(pm->photons_emitted), ull(pm->caustic_photons_emitted),
                ull(pm->global_photons_stored), ull(pm->caustic_photons_stored),
                pm->photon_trace_seconds, pm->global_gather_radius, pm->caustic_gather_radius);
  if (const auto& cache = prepared.irradiance_cache)
    std::printf("  irradiance cache: %llu records, %llu gather rays in %.3f s\n",
                ull(cache->records), ull(cache->gather_rays), cache->seconds);
  if (const auto& r = prepared.radiosity)
    std::printf("  radiosity: %llu patches, %llu elements, %llu rays in %.3f s\n", ull(r->patches),
                ull(r->elements), ull(r->rays), r->solve_seconds);
  std::string error;
  if (!write_rgba_image(out, session.image(), session.region_width(), session.region_height(),
                        &error)) {
    std::fprintf(stderr, "cannot write %s: %s\n", out.c_str(), error.c_str());
    return 1;
  }
  std::printf("wrote %s\n", out.c_str());
  if (!passes_prefix.empty()) {
    // Reassemble each light pass from the tiles and write it as an RGBA image.
    const int w = session.region_width(), h = session.region_height();
    const char* names[kPassCount] = {"direct", "indirect", "caustics", "photon_map"};
    std::vector<std::vector<float>> images(kPassCount, std::vector<float>(size_t(w) * h * 4, 1.0f));
    for (const Tile& t : tiles) {
      for (int row = 0; row < t.height; ++row)
        for (int col = 0; col < t.width; ++col)
          for (int k = 0; k < kPassCount; ++k)
            for (int c = 0; c < 3; ++c)
              images[k][(size_t(t.y + row) * w + t.x + col) * 4 + c] =
                  t.passes[(size_t(row) * t.width + col) * kPassFloats + 3 * k + c];
    }
    for (int k = 0; k < kPassCount; ++k) {
      const std::string path = passes_prefix + "_" + names[k] + ".exr";
      if (!write_rgba_image(path, images[k], w, h, &error)) {
        std::fprintf(stderr, "cannot write %s: %s\n", path.c_str(), error.c_str());
        return 1;
      }
      std::printf("wrote %s\n", path.c_str());
    }
  }
  return 0;
}
