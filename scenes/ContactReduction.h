#pragma once
// ODE's trimesh colliders stop at the contact limit in the order they meet triangles, so a low
// limit keeps a cluster on one side of the touching area: the solver then lets a body sink or tip
// where it has no contact. The simulation asks ODE for many contacts and keeps a spread-out
// subset: the deepest, then repeatedly the one farthest from those already kept.
#include <cstddef>
#include <span>
#include <vector>

#include <ode/ode.h>

namespace cdb {

class ContactPicker {
 public:
  // Indices into contacts[0, found) of at most `keep` contacts, in a deterministic order. The span
  // stays valid until the next call.
  [[nodiscard]] std::span<const std::size_t> pick(std::span<const dContact> contacts, std::size_t found,
                                                  std::size_t keep);

 private:
  std::vector<std::size_t> chosen_;
  std::vector<double> distance_;  // squared, to the nearest chosen contact
};

}  // namespace cdb
