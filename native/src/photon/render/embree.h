#pragma once
// The Embree API Photon uses, for Embree 3 (Debian 12) and Embree 4 (Debian 13 and later). The
// queries differ: Embree 4 replaced the intersect context by optional per-query arguments and
// dropped the ray streams (rtcIntersect1M). Everything else Photon calls is the same in both.

#if PHOTON_EMBREE_MAJOR >= 4
#include <embree4/rtcore.h>
#else
#include <embree3/rtcore.h>
#endif

namespace photon::embree {

// A triangle geometry inside a mesh's BVH, visible to every ray: visibility is decided by the
// instance's mask alone. Embree 3 gives new geometry the mask 0xFFFFFFFF, Embree 4 gives it 1,
// which would hide meshes from every ray whose mask lacks bit 0.
inline RTCGeometry new_triangle_geometry(RTCDevice device) {
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryMask(geom, 0xFFFFFFFFu);
  return geom;
}

inline void intersect1(RTCScene scene, RTCRayHit* rayhit) {
#if PHOTON_EMBREE_MAJOR >= 4
  rtcIntersect1(scene, rayhit);
#else
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect1(scene, &context, rayhit);
#endif
}

// Rays that start close together and point alike (camera rays of one tile). Embree 3 traces
// them as a stream; Embree 4 has no streams and traces them one by one with the coherent hint.
inline void intersect_coherent(RTCScene scene, RTCRayHit* rayhits, unsigned count) {
#if PHOTON_EMBREE_MAJOR >= 4
  RTCIntersectArguments args;
  rtcInitIntersectArguments(&args);
  args.flags = RTC_RAY_QUERY_FLAG_COHERENT;
  for (unsigned i = 0; i < count; ++i) rtcIntersect1(scene, &rayhits[i], &args);
#else
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  rtcIntersect1M(scene, &context, rayhits, count, sizeof(RTCRayHit));
#endif
}

inline void occluded1(RTCScene scene, RTCRay* ray) {
#if PHOTON_EMBREE_MAJOR >= 4
  rtcOccluded1(scene, ray);
#else
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcOccluded1(scene, &context, ray);
#endif
}

}  // namespace photon::embree
