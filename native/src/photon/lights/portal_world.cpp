#include "photon/lights/portal_world.h"

#include <algorithm>

namespace photon {

PortalWorldEmitter::PortalWorldEmitter(const Emitter& world, PortalSet portals)
    : world_(world), portals_(std::move(portals)) {}

LightSampleU PortalWorldEmitter::draw_li(Sampler& sampler) const {
  LightSampleU u;
  u.pick = sampler.get_1d();
  u.uv = sampler.get_2d();
  return u;
}

float PortalWorldEmitter::pdf_li_at_infinity(const Vec3& p, const Vec3& direction) const {
  const float world = world_pdf(direction);
  if (portals_.facing(p) == 0) return world;
  return kPortalShare * portals_.pdf(p, direction) + (1.0f - kPortalShare) * world;
}

bool PortalWorldEmitter::sample_li(const Vec3& p, const LightSampleU& u,
                                   const PhotonFrame* bidirectional, LightSample* out) const {
  if (bidirectional) return world_.sample_li(p, u, bidirectional, out);
  Vec3 wi;
  if (u.pick < kPortalShare && portals_.facing(p) > 0) {
    float portal_pdf;
    if (!portals_.sample(p, u.pick / kPortalShare, u.uv, &wi, &portal_pdf)) return false;
  } else {
    // The world's own directions, as its bidirectional light sample draws them (the frame only
    // sets densities this does not read).
    const PhotonFrame frame;
    LightSample ws;
    if (!world_.sample_li(p, u, &frame, &ws)) return false;
    wi = ws.wi;
  }
  const float pdf = pdf_li_at_infinity(p, wi);
  const Vec3 l = world_.radiance_at_infinity(wi);
  if (!(pdf > 0.0f) || is_black(l)) return false;
  out->wi = wi;
  out->distance = INFINITY;
  out->pdf = pdf;
  out->weight = l / pdf;
  out->surface_normal = Vec3(0.0f);
  return is_finite(out->weight);
}

float PortalWorldEmitter::line_pdf(const PhotonFrame& frame, const Vec3& point,
                                   const Vec3& direction, int crossings) const {
  // The world's technique: the light's direction from its density, then a uniform point of the
  // disc across that direction covering the scene (lines further out it never makes).
  const Vec3 to_center = frame.center - point;
  const Vec3 off_axis = to_center - direction * dot(to_center, direction);
  const float world = length_squared(off_axis) <= frame.radius * frame.radius
                          ? world_pdf(-direction) * scene_disc_pdf(frame)
                          : 0.0f;
  // The portals' technique: a point picked by area, a cosine-weighted direction (cos / pi per
  // solid angle, 1 / cos per projected area), for each portal the line crosses.
  const float portal = static_cast<float>(crossings) / (kPi * portals_.total_area());
  return kPortalShare * portal + (1.0f - kPortalShare) * world;
}

bool PortalWorldEmitter::sample_le(const PhotonFrame& frame, float u_rest, Vec2 u_pos, Vec2 u_dir,
                                   bool bidirectional, EmittedPhoton* out) const {
  if (bidirectional) return world_.sample_le(frame, u_rest, u_pos, u_dir, true, out);
  out->power = Vec3(0.0f);
  Vec3 point, d;  // a point of the line, and the way the light travels along it
  int crossings;
  if (u_rest < kPortalShare) {
    portals_.sample_line(u_rest / kPortalShare, u_pos, u_dir, &point, &d);
    // It crosses the portal it was drawn on (the test could miss an edge point by rounding).
    crossings = std::max(portals_.crossings(point, d), 1);
  } else {
    EmittedPhoton w;
    const float u_world = std::min((u_rest - kPortalShare) / (1.0f - kPortalShare), 0.99999994f);
    if (!world_.sample_le(frame, u_world, u_pos, u_dir, true, &w)) return false;
    point = w.ray.origin;
    d = w.ray.direction;
    crossings = portals_.crossings(point, d);
  }
  // From 2R before the scene's centre along the line: the photon meets whatever lies outside
  // the portals (a wall around the window, a tree) as light from the world does.
  const float back = dot(frame.center - point, d) - 2.0f * frame.radius;
  set_emitted_ray(point + d * back, d, &out->ray);
  const float pdf = line_pdf(frame, point, d, crossings);
  if (!(pdf > 0.0f)) return false;
  out->power = world_.radiance_at_infinity(-d) / pdf;
  return is_finite(out->power) && !is_black(out->power);
}

}  // namespace photon
