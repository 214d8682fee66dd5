// A frame rendered through a named backend of 1024 blocks x 32 words with the default
// kernel options, for the end-to-end tests that compare the golden model and the RTL;
// every answer under the ray-level exact check (rt::ExactCheck: a disagreement throws).
#pragma once

#include <string>

#include "backends/backend.h"
#include "sw/fmpp/device.h"
#include "sw/render/exact_check.h"
#include "sw/render/render.h"

namespace test_render {

// Renders s at size x size through `backend`; *st (if given) gets the kernels' counters.
inline rt::Image render_through(const std::string& backend, const rt::Scene& s, int size,
                                fmpp::isect::KernelStats* st = nullptr) {
  auto be = fmpp::make_backend(backend, fmpp::Config{1024, 32});
  fmpp::Device dev(be->bus());
  rt::FmppIntersector fi(dev, s.triangles, fmpp::isect::KernelOptions{});
  rt::RenderOptions ro;
  ro.width = ro.height = size;
  rt::ExactCheck check(fi, s.triangles, "the end-to-end test's " + backend + " render");
  rt::Image img = rt::render(s, check, ro, nullptr);
  be->finish();
  if (st) *st = fi.stats();
  return img;
}

}  // namespace test_render
