// What every ray-parallel form shares (see ray_form.h).
#include "sw/isect/pass/ray_form.h"

#include <algorithm>

namespace fmpp::isect {

bool RayForm::usable(size_t k, std::vector<int>* refused) const {
  const Broadcast& b = broadcasts[k];
  if (!b.refused()) return true;
  if (std::find(refused->begin(), refused->end(), b.tri) == refused->end()) refused->push_back(b.tri);
  return false;
}

std::vector<size_t> RayForm::usable(std::vector<size_t> order, std::vector<int>* refused, uint64_t* dropped) const {
  const size_t n = order.size();
  order.erase(std::remove_if(order.begin(), order.end(), [&](size_t k) { return !usable(k, refused); }), order.end());
  *dropped += n - order.size();
  return order;
}

void RayForm::keep_usable(std::vector<char>* marks, std::vector<int>* refused) const {
  for (size_t k = 0; k < marks->size(); ++k) {
    if ((*marks)[k] && !usable(k, refused)) (*marks)[k] = 0;
  }
}

size_t RayForm::host_triangles() const {
  size_t n = host.size();
  for (const Broadcast& b : broadcasts) n += b.host;
  return n;
}

}  // namespace fmpp::isect
