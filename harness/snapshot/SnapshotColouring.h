#pragma once
// The colours of a snapshot (thesis Figures 4.1, 4.5, 4.10 with a strategy's answer on them): one
// colour per potentially colliding set, grey for what the culling pruned, fixed objects pale, and
// which objects are in a colliding pair (outlined in the picture). Without a strategy: one colour
// per body group.
#include <cstddef>
#include <span>
#include <vector>

#include "culling/PotentiallyCollidingSets.h"
#include "culling/exact/ObjectPair.h"
#include "render/Image.h"
#include "scenes/SceneGeometry.h"

namespace cdb {

// Set k is painted kSetPalette[k % size]: nine hues far apart (Matplotlib's tab10 without its
// grey), so sets that far apart in the list share a colour.
inline constexpr Rgb kSetPalette[] = {{31, 119, 180},  {255, 127, 14},  {44, 160, 44},
                                      {214, 39, 40},   {148, 103, 189}, {140, 86, 75},
                                      {227, 119, 194}, {188, 189, 34},  {23, 190, 207}};
inline constexpr std::size_t kSetPaletteSize = std::size(kSetPalette);
inline constexpr Rgb kPrunedColour{190, 190, 190};
inline constexpr Rgb kOutlineColour{15, 15, 15};

[[nodiscard]] constexpr Rgb setColour(std::size_t set) {
  return kSetPalette[set % kSetPaletteSize];
}

struct ObjectColouring {
  std::vector<Rgb> colour;      // per object
  std::vector<int> setOf;       // per object: its set, or -1 (pruned, or colouring by group)
  std::vector<bool> colliding;  // per object: in one of the colliding pairs
};

// By the sets a culling strategy left: every member of set k in setColour(k) (a member of several
// sets in its first set's), objects in no set in kPrunedColour. Throws RunError for a member or a
// pair outside the scene.
[[nodiscard]] ObjectColouring colourBySets(std::size_t objectCount,
                                           const PotentiallyCollidingSets& sets,
                                           std::span<const ObjectPair> colliding);

// Fixed objects (the planes of a trough, which a set often holds) in their colour made pale, so
// that the moving objects stand out from the ground they lie on.
void paleFixedObjects(const SceneGeometry& scene, ObjectColouring& colouring);
[[nodiscard]] constexpr Rgb pale(Rgb c) {
  const auto up = [](std::uint8_t v) { return static_cast<std::uint8_t>(v + (255 - v) * 3 / 5); };
  return {up(c.r), up(c.g), up(c.b)};
}

// By body group (fixed bodies in a slate grey, moving groups in warm colours), for a picture of
// the scene alone.
[[nodiscard]] ObjectColouring colourByGroup(const SceneGeometry& scene,
                                            std::span<const ObjectPair> colliding);

}  // namespace cdb
