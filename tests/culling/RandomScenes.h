#pragma once
// Random test scenes of the culling tests: tori (optionally with two planes) at random poses in a
// cube centred on the origin, small enough that many of them touch or interpenetrate; the dragon.
#include <cstdint>
#include <optional>

#include "scenes/MeshLoader.h"
#include "tests/common/RandomScenes.h"
#include "tests/scenes/TestAssets.h"

namespace cdb::testing {

// `tori` tori at translations in [-halfExtent, halfExtent)^3, `frames` times.
inline RandomScene randomTori(int tori, double halfExtent, int frames, std::uint64_t seed,
                              bool withPlanes = false) {
  RandomToriSpec spec;
  spec.count = tori;
  spec.lo = -halfExtent;
  spec.hi = halfExtent;
  spec.frames = frames;
  spec.seed = seed;
  spec.withPlanes = withPlanes;
  return randomTori(spec);
}

// The dragon of the asset path scaled to unit size, or nothing when it is not there.
inline std::optional<Mesh> loadUnitDragon() {
  const auto path = cdb::test::findTestAsset("dragon_vrip_res3");
  if (!path) return std::nullopt;
  Mesh mesh = loadMesh(*path).mesh;
  normaliseMesh(mesh, 1.0);
  return mesh;
}

}  // namespace cdb::testing
