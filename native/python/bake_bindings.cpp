// Python bindings of the lighting bake (bake.h) and the lightmap helpers (lightmap.h), part of
// the `_photon` module. Arrays in and out are numpy; the bake runs without the GIL.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <signal.h>

#include <atomic>
#include <cstring>
#include <stdexcept>

#include "photon/session/bake.h"
#include "photon/session/lightmap.h"
#include "stats_bindings.h"

namespace py = pybind11;
using namespace photon;

namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;
using IntArray = py::array_t<int32_t, py::array::c_style | py::array::forcecast>;
using ByteArray = py::array_t<uint8_t, py::array::c_style | py::array::forcecast>;

template <typename T>
py::array_t<float> vec_array(const std::vector<T>& v, size_t components) {
  py::array_t<float> a({v.size(), components});
  if (!v.empty()) std::memcpy(a.mutable_data(), v.data(), v.size() * sizeof(T));
  return a;
}

std::vector<BakePoint> points_from(const IntArray& instances, const IntArray& triangles,
                                   const FloatArray& barycentrics) {
  const size_t n = static_cast<size_t>(instances.size());
  if (static_cast<size_t>(triangles.size()) != n ||
      static_cast<size_t>(barycentrics.size()) != 2 * n)
    throw std::invalid_argument(
        "bake points: instances (N,), triangles (N,) and barycentrics (N, 2) must agree");
  std::vector<BakePoint> points(n);
  const int32_t* inst = instances.data();
  const int32_t* tri = triangles.data();
  const float* b = barycentrics.data();
  for (size_t i = 0; i < n; ++i) {
    // Negative indices become huge and are reported as invalid points.
    points[i].instance = static_cast<uint32_t>(inst[i]);
    points[i].triangle = static_cast<uint32_t>(tri[i]);
    points[i].u = b[2 * i];
    points[i].v = b[2 * i + 1];
  }
  return points;
}

py::dict result_dict(const BakeResult& r) {
  if (!r.error.empty()) throw std::runtime_error("Photon bake: " + r.error);
  py::dict d;
  d["radiance"] = vec_array(r.radiance, 3);
  d["position"] = vec_array(r.position, 3);
  d["normal"] = vec_array(r.normal, 3);
  py::array_t<uint8_t> status(r.status.size());
  if (!r.status.empty()) std::memcpy(status.mutable_data(), r.status.data(), r.status.size());
  d["status"] = status;
  d["warnings"] = r.warnings;
  d["cancelled"] = r.cancelled;
  d["stats"] = photon_python::bake_stats(r);
  return d;
}

template <typename T, typename Array>
std::vector<T> image_rows(const Array& a, size_t count, size_t components, const char* what) {
  if (static_cast<size_t>(a.size()) != count * components)
    throw std::invalid_argument(std::string(what) + ": expected " +
                                std::to_string(count * components) + " values");
  std::vector<T> out(count);
  if (count) std::memcpy(out.data(), a.data(), count * sizeof(T));
  return out;
}

// Ctrl-C during a blocking bake. Blender's background-mode SIGINT handler only sets a flag that
// renders poll (and kills Blender on the second Ctrl-C), so an operator never sees the first
// one. While a bake runs, this handler cancels the watched session directly (an atomic store is
// async-signal-safe) and then calls the previous handler, so Blender's own behaviour is kept.
std::atomic<BakeSession*> g_sigint_session{nullptr};
std::atomic<bool> g_sigint_received{false};
struct sigaction g_previous_sigint;
bool g_sigint_installed = false;

void on_sigint(int signal_number) {
  g_sigint_received.store(true);
  if (BakeSession* session = g_sigint_session.load()) session->cancel();
  const struct sigaction& previous = g_previous_sigint;
  if (previous.sa_flags & SA_SIGINFO) {
    if (previous.sa_sigaction) previous.sa_sigaction(signal_number, nullptr, nullptr);
  } else if (previous.sa_handler != SIG_DFL && previous.sa_handler != SIG_IGN &&
             previous.sa_handler != nullptr) {
    previous.sa_handler(signal_number);
  }
}

void watch_sigint(BakeSession* session) {
  g_sigint_session.store(session);
  if (g_sigint_installed) return;
  g_sigint_received.store(false);
  struct sigaction action {};
  action.sa_handler = on_sigint;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  if (sigaction(SIGINT, &action, &g_previous_sigint) == 0) g_sigint_installed = true;
}

bool unwatch_sigint() {
  g_sigint_session.store(nullptr);
  if (g_sigint_installed) {
    sigaction(SIGINT, &g_previous_sigint, nullptr);
    g_sigint_installed = false;
  }
  return g_sigint_received.load();
}

}  // namespace

void bind_bake(py::module_& m) {
  m.def(
      "watch_sigint", [](BakeSession* session) { watch_sigint(session); },
      py::arg("session") = nullptr,
      "Until unwatch_sigint(): Ctrl-C (SIGINT) cancels `session` (None: only noted; call again "
      "with the session once it exists), then reaches the handler that was installed before.");
  m.def("unwatch_sigint", &unwatch_sigint,
        "Restores the SIGINT handler of before watch_sigint(); True when a SIGINT came.");
  m.def(
      "sigint_received", [] { return g_sigint_received.load(); },
      "True when a SIGINT came since watch_sigint() installed its handler.");

  m.attr("BAKE_OK") = static_cast<int>(kBakeOk);
  m.attr("BAKE_INVALID_POINT") = static_cast<int>(kBakeInvalidPoint);
  m.attr("BAKE_UNSUPPORTED") = static_cast<int>(kBakeUnsupported);
  m.attr("BAKE_NON_FINITE") = static_cast<int>(kBakeNonFinite);
  m.attr("BAKE_NOT_DONE") = static_cast<int>(kBakeNotDone);

  py::class_<BakeSession>(m, "BakeSession",
                          "Bakes view-independent radiance at surface points on a background "
                          "thread: start(), poll progress/status/finished, then result().")
      .def(py::init([](std::shared_ptr<Scene> scene, const RenderSettings& settings,
                       const IntArray& instances, const IntArray& triangles,
                       const FloatArray& barycentrics, bool brighter_side) {
             BakeOptions options;
             options.brighter_side = brighter_side;
             return std::make_unique<BakeSession>(std::move(scene), settings, options,
                                                  points_from(instances, triangles, barycentrics));
           }),
           py::arg("scene"), py::arg("settings"), py::arg("instances"), py::arg("triangles"),
           py::arg("barycentrics"), py::arg("brighter_side") = true)
      .def("start", &BakeSession::start)
      .def("cancel", &BakeSession::cancel)
      .def("stop_preparation", &BakeSession::stop_preparation)
      .def("wait", &BakeSession::wait, py::call_guard<py::gil_scoped_release>())
      .def_property_readonly("finished", &BakeSession::finished)
      .def_property_readonly("cancelled", &BakeSession::cancelled)
      .def_property_readonly("preparing", &BakeSession::preparing)
      .def_property_readonly("progress", &BakeSession::progress)
      .def_property_readonly("status", &BakeSession::status)
      .def_property_readonly("error", &BakeSession::error,
                             "Why the bake failed (status 'Failed'); empty otherwise.")
      .def(
          "result", [](const BakeSession& s) { return result_dict(s.result()); },
          "Once finished: dict of radiance/position/normal (N, 3) float32, status (N,) uint8 "
          "(BAKE_*), warnings, cancelled, stats. Raises RuntimeError when the integrator "
          "cannot bake.");

  m.def(
      "bake",
      [](std::shared_ptr<Scene> scene, const RenderSettings& settings, const IntArray& instances,
         const IntArray& triangles, const FloatArray& barycentrics, bool brighter_side) {
        const std::vector<BakePoint> points = points_from(instances, triangles, barycentrics);
        BakeOptions options;
        options.brighter_side = brighter_side;
        BakeResult r;
        {
          py::gil_scoped_release release;
          r = bake_points(*scene, settings, options, points, PrepareControl{});
        }
        return result_dict(r);
      },
      py::arg("scene"), py::arg("settings"), py::arg("instances"), py::arg("triangles"),
      py::arg("barycentrics"), py::arg("brighter_side") = true,
      "Synchronous bake: radiance leaving each surface point (Scene.instances index, triangle "
      "in the order the mesh was given, barycentrics (u, v) of corners 1 and 2), as "
      "BakeSession.result(). settings.samples is the number of samples per point; "
      "brighter_side shades both sides of each point and keeps the brighter.");

  m.def(
      "rasterize_uv",
      [](const FloatArray& uvs, py::object positions, int width, int height) {
        if (uvs.size() % 6) throw std::invalid_argument("uvs: (T, 3, 2) expected");
        const size_t t = static_cast<size_t>(uvs.size()) / 6;
        if (width <= 0 || height <= 0 || width > 32768 || height > 32768)
          throw std::invalid_argument("lightmap size must be within 1..32768");
        std::vector<Vec2> uv = image_rows<Vec2>(uvs, 3 * t, 2, "uvs");
        std::vector<Vec3> pos;
        if (!positions.is_none())
          pos = image_rows<Vec3>(positions.cast<FloatArray>(), 3 * t, 3, "positions");
        std::vector<TexelPoint> texels;
        {
          py::gil_scoped_release release;
          texels = rasterize_uv_triangles(uv.data(), pos.empty() ? nullptr : pos.data(), t, width,
                                          height);
        }
        const size_t n = texels.size();
        py::array_t<int32_t> texel(n), triangle(n);
        py::array_t<float> bary({n, size_t{2}}), size(n);
        for (size_t i = 0; i < n; ++i) {
          texel.mutable_data()[i] = static_cast<int32_t>(texels[i].texel);
          triangle.mutable_data()[i] = static_cast<int32_t>(texels[i].triangle);
          bary.mutable_data()[2 * i] = texels[i].u;
          bary.mutable_data()[2 * i + 1] = texels[i].v;
          size.mutable_data()[i] = texels[i].world_size;
        }
        return py::make_tuple(texel, triangle, bary, size);
      },
      py::arg("uvs"), py::arg("positions"), py::arg("width"), py::arg("height"),
      "Texel centres covered by UV triangles: (texel index y*width+x, triangle, barycentrics "
      "(n, 2), world size of a texel). uvs (T, 3, 2); positions (T, 3, 3) world or None.");

  m.def(
      "filter_lightmap",
      [](const FloatArray& values, const ByteArray& covered, const FloatArray& positions,
         const FloatArray& normals, const FloatArray& world_size, int width, int height, int radius,
         int dilate) {
        if (width <= 0 || height <= 0) throw std::invalid_argument("bad lightmap size");
        const size_t count = static_cast<size_t>(width) * height;
        const auto v = image_rows<Vec3>(values, count, 3, "values");
        const auto c = image_rows<uint8_t>(covered, count, 1, "covered");
        const auto p = image_rows<Vec3>(positions, count, 3, "positions");
        const auto n = image_rows<Vec3>(normals, count, 3, "normals");
        const auto s = image_rows<float>(world_size, count, 1, "world_size");
        LightmapFilter filter;
        filter.radius = std::clamp(radius, 0, 16);
        filter.dilate = std::clamp(dilate, 0, 256);
        std::vector<Vec3> out;
        std::vector<uint8_t> mask;
        {
          py::gil_scoped_release release;
          out = filter_lightmap(width, height, v, c, p, n, s, filter, &mask);
        }
        py::array_t<float> image(
            {static_cast<size_t>(height), static_cast<size_t>(width), size_t{3}});
        std::memcpy(image.mutable_data(), out.data(), count * sizeof(Vec3));
        py::array_t<uint8_t> coverage({static_cast<size_t>(height), static_cast<size_t>(width)});
        std::memcpy(coverage.mutable_data(), mask.data(), count);
        return py::make_tuple(image, coverage);
      },
      py::arg("values"), py::arg("covered"), py::arg("positions"), py::arg("normals"),
      py::arg("world_size"), py::arg("width"), py::arg("height"), py::arg("radius") = 1,
      py::arg("dilate") = 4,
      "Surface-aware 2D filter and gutter dilation of a baked lightmap; returns "
      "(image (h, w, 3), coverage (h, w)). Rows go upwards from v = 0.");

  m.def(
      "upsample_lightmap",
      [](const FloatArray& image, int factor) {
        if (image.ndim() != 3 || image.shape(2) != 3)
          throw std::invalid_argument("upsample_lightmap: image (h, w, 3) expected");
        if (factor < 1 || factor > 64) throw std::invalid_argument("factor must be within 1..64");
        const int h = static_cast<int>(image.shape(0)), w = static_cast<int>(image.shape(1));
        py::array_t<float> rgba(
            {static_cast<size_t>(h) * factor, static_cast<size_t>(w) * factor, size_t{4}});
        const Vec3* values = reinterpret_cast<const Vec3*>(image.data());
        float* out = rgba.mutable_data();
        {
          py::gil_scoped_release release;
          upsample_lightmap_rgba(values, w, h, factor, out);
        }
        return rgba;
      },
      py::arg("image"), py::arg("factor"),
      "Bilinear upsampling of a filtered lightmap (h, w, 3) by an integer factor; returns RGBA "
      "(h * factor, w * factor, 4) with alpha 1, rows upwards as the input.");
}
