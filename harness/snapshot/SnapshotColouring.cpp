#include "harness/snapshot/SnapshotColouring.h"

#include <string>

#include "core/Errors.h"

namespace cdb {

namespace {

void markColliding(ObjectColouring& c, std::span<const ObjectPair> colliding) {
  for (const ObjectPair& p : colliding) {
    if (p.a >= c.colliding.size() || p.b >= c.colliding.size())
      throw RunError("colliding pair (" + std::to_string(p.a) + ", " + std::to_string(p.b) +
                     ") outside the scene of " + std::to_string(c.colliding.size()) + " objects");
    c.colliding[p.a] = c.colliding[p.b] = true;
  }
}

}  // namespace

ObjectColouring colourBySets(std::size_t objectCount, const PotentiallyCollidingSets& sets,
                             std::span<const ObjectPair> colliding) {
  ObjectColouring c;
  c.colour.assign(objectCount, kPrunedColour);
  c.setOf.assign(objectCount, -1);
  c.colliding.assign(objectCount, false);
  for (std::size_t k = 0; k < sets.size(); ++k) {
    for (const SetMember& m : sets[k].members) {
      if (m.object >= objectCount)
        throw RunError("set " + std::to_string(k + 1) + " names object " +
                       std::to_string(m.object) + " of a scene of " + std::to_string(objectCount));
      if (c.setOf[m.object] >= 0) continue;  // in an earlier set too: the first one's colour
      c.setOf[m.object] = static_cast<int>(k);
      c.colour[m.object] = setColour(k);
    }
  }
  markColliding(c, colliding);
  return c;
}

void paleFixedObjects(const SceneGeometry& scene, ObjectColouring& colouring) {
  for (std::size_t o = 0; o < scene.objectCount() && o < colouring.colour.size(); ++o)
    if (scene.objects[o].fixed) colouring.colour[o] = pale(colouring.colour[o]);
}

ObjectColouring colourByGroup(const SceneGeometry& scene, std::span<const ObjectPair> colliding) {
  static constexpr Rgb kFixed{150, 158, 172};
  static constexpr Rgb kMoving[] = {
      {222, 164, 96}, {120, 170, 210}, {150, 196, 120}, {204, 132, 160}};
  ObjectColouring c;
  c.setOf.assign(scene.objectCount(), -1);
  c.colliding.assign(scene.objectCount(), false);
  std::vector<std::string> movingGroups;
  for (const SceneObject& o : scene.objects) {
    if (o.fixed) {
      c.colour.push_back(kFixed);
      continue;
    }
    std::size_t g = 0;
    while (g < movingGroups.size() && movingGroups[g] != o.group) ++g;
    if (g == movingGroups.size()) movingGroups.push_back(o.group);
    c.colour.push_back(kMoving[g % std::size(kMoving)]);
  }
  markColliding(c, colliding);
  return c;
}

}  // namespace cdb
