// Embree behind the tracer's Intersector interface (see embree_intersector.h).
#include "sw/embree/embree_intersector.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rt {

using fmpp::isect::Hit;
using fmpp::isect::Ray;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

const char* error_name(RTCError e) {
  switch (e) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_UNKNOWN: return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
  }
  return "error";
}

void check(RTCDevice dev, const char* what) {
  const RTCError e = rtcGetDeviceError(dev);
  if (e != RTC_ERROR_NONE) throw std::runtime_error(std::string("Embree: ") + what + ": " + error_name(e));
}

// The ray's id carries exclude + 1 (0: none); a candidate hit on that triangle is
// rejected, so Embree goes on to the next one, as the reference skips it.
void reject_excluded(const RTCFilterFunctionNArguments* args) {
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const unsigned excluded = RTCRayN_id(args->ray, args->N, i);
    if (excluded != 0 && RTCHitN_primID(args->hit, args->N, i) == excluded - 1) args->valid[i] = 0;
  }
}

// The smallest float >= x (x finite or infinite), so that a ray's float interval holds
// its double one.
float float_up(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

// The largest float <= x, x >= 0.
float float_down(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) > x) f = std::nextafter(f, 0.0f);
  return f;
}

}  // namespace

EmbreeIntersector::EmbreeIntersector(const std::vector<fmpp::isect::Triangle>& tris, double spawn_margin,
                                     const EmbreeOptions& opt)
    : spawn_margin_(spawn_margin), stream_(opt.stream) {
  if (opt.threads < 1) throw std::invalid_argument("EmbreeIntersector: threads " + std::to_string(opt.threads) + " < 1");
  if (tris.size() >= std::numeric_limits<unsigned>::max()) {
    throw std::invalid_argument("EmbreeIntersector: " + std::to_string(tris.size()) + " triangles, too many for Embree");
  }
  const std::string config = "threads=" + std::to_string(opt.threads);
  device_ = rtcNewDevice(config.c_str());
  if (!device_) throw std::runtime_error("Embree: rtcNewDevice(\"" + config + "\"): " + error_name(rtcGetDeviceError(nullptr)));
  try {
    const auto t0 = std::chrono::steady_clock::now();
    scene_ = rtcNewScene(device_);
    check(device_, "rtcNewScene");
    if (opt.robust) rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    check(device_, "rtcNewGeometry");
    // Every triangle its own three vertices: the scene's triangles carry no sharing, and
    // the float rounding of a vertex is the same wherever it appears.
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), 3 * tris.size()));
    auto* idx = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), tris.size()));
    check(device_, "rtcSetNewGeometryBuffer");
    for (size_t t = 0; t < tris.size(); ++t) {
      for (int k = 0; k < 3; ++k) {
        for (int c = 0; c < 3; ++c) v[9 * t + 3 * k + c] = static_cast<float>(tris[t].p[k][c]);
        idx[3 * t + k] = static_cast<unsigned>(3 * t + k);
      }
    }
    rtcSetGeometryIntersectFilterFunction(geom, reject_excluded);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene_, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene_);
    check(device_, "building the scene");
    build_seconds_ = seconds_since(t0);
  } catch (...) {
    if (scene_) rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
    throw;
  }
}

EmbreeIntersector::~EmbreeIntersector() {
  rtcReleaseScene(scene_);
  rtcReleaseDevice(device_);
}

void EmbreeIntersector::reset_counts() {
  for (int k = 0; k < kNumBatchKinds; ++k) {
    rays_[k] = 0;
    seconds_[k] = 0;
  }
}

std::string EmbreeIntersector::version() const {
  const ssize_t v = rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_VERSION);
  return std::to_string(v / 10000) + "." + std::to_string(v / 100 % 100) + "." + std::to_string(v % 100);
}

std::vector<Hit> EmbreeIntersector::intersect(const std::vector<Ray>& rays) {
  std::vector<RTCRayHit> rh(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) {
    const Ray& r = rays[i];
    RTCRay& e = rh[i].ray;
    e.org_x = static_cast<float>(r.o.x);
    e.org_y = static_cast<float>(r.o.y);
    e.org_z = static_cast<float>(r.o.z);
    e.dir_x = static_cast<float>(r.d.x);
    e.dir_y = static_cast<float>(r.d.y);
    e.dir_z = static_cast<float>(r.d.z);
    e.tnear = float_down(r.tmin);
    e.tfar = float_up(r.tmax);
    e.time = 0;
    e.mask = ~0u;
    e.id = r.exclude >= 0 ? static_cast<unsigned>(r.exclude) + 1 : 0;
    e.flags = 0;
    rh[i].hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh[i].hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh[i].hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  }
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  if (stream_) ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  const auto t0 = std::chrono::steady_clock::now();
  if (stream_) {
    // rtcIntersect1M takes an unsigned count: a batch beyond it goes in pieces.
    constexpr size_t kMaxStream = size_t{1} << 30;
    for (size_t i = 0; i < rh.size(); i += kMaxStream) {
      rtcIntersect1M(scene_, &ctx, rh.data() + i, static_cast<unsigned>(std::min(kMaxStream, rh.size() - i)),
                     sizeof(RTCRayHit));
    }
  } else {
    for (RTCRayHit& r : rh) rtcIntersect1(scene_, &ctx, &r);
  }
  seconds_[static_cast<int>(kind_)] += seconds_since(t0);
  rays_[static_cast<int>(kind_)] += rays.size();
  std::vector<Hit> hits(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) {
    if (rh[i].hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
    hits[i].tri = static_cast<int>(rh[i].hit.primID);
    hits[i].t = rh[i].ray.tfar;
  }
  return hits;
}

}  // namespace rt
