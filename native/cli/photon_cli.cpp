// photon_cli: renders a built-in scene without Blender, e.g.
//   photon_cli --scene cornell --width 256 --height 256 --samples 64 --out cornell.exr
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "photon/image_io.h"
#include "photon/render_session.h"
#include "photon/test_scenes.h"

using namespace photon;

static void usage() {
  std::printf(
      "usage: photon_cli [--scene cornell] [--width N] [--height N] [--samples N]\n"
      "                  [--max-depth N] [--seed N] [--threads N] [--tile-size N] --out FILE\n");
}

int main(int argc, char** argv) {
  RenderSettings settings;
  settings.full_width = settings.full_height = 256;
  settings.samples = 16;
  std::string scene_name = "cornell", out;
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
    else if (!std::strcmp(argv[i], "--out")) out = next("--out");
    else {
      usage();
      return 2;
    }
  }
  if (out.empty() || scene_name != "cornell") {
    usage();
    return 2;
  }
  settings.x1 = settings.full_width;
  settings.y1 = settings.full_height;
  auto scene = std::make_shared<Scene>(make_cornell_box());
  const float aspect = static_cast<float>(settings.full_width) / settings.full_height;
  scene->camera.window_min_x = scene->camera.window_min_y * aspect;
  scene->camera.window_max_x = scene->camera.window_max_y * aspect;

  RenderSession session(scene, settings);
  session.start();
  session.wait();
  for (const std::string& w : session.warnings()) std::fprintf(stderr, "warning: %s\n", w.c_str());
  const RenderStats stats = session.stats();
  std::printf("rendered %dx%d, %d spp, %d threads: build %.3f s, render %.3f s\n",
              settings.full_width, settings.full_height, settings.samples, stats.threads,
              stats.build_seconds, stats.render_seconds);
  std::string error;
  if (!write_rgba_image(out, session.image(), session.region_width(), session.region_height(),
                        &error)) {
    std::fprintf(stderr, "cannot write %s: %s\n", out.c_str(), error.c_str());
    return 1;
  }
  std::printf("wrote %s\n", out.c_str());
  return 0;
}
