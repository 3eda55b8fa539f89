#pragma once
// harness/snapshot/, the room of `cdbench snapshot`. SnapshotOptions is what was asked for,
// SnapshotColouring gives each object its colour from a strategy's answer, SnapshotLegend lays out
// the band under the picture, SnapshotPicture renders one picture, PngWriter encodes it and
// AnimationWriter makes an animation of a frame range. SnapshotCommand (this file) runs them.
//
// `cdbench snapshot`: a picture of a scenario's frame (thesis Figures 4.1, 4.5, 4.10), simulated
// from the config or read from a pose recording, optionally with a culling strategy's answer on it
// (one colour per potentially colliding set, pruned objects grey, colliding objects outlined), a
// legend under it, and beside it a JSON file with what the picture shows. With a frame range: one
// picture per frame and an animation made from them.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <vector>

#include "harness/snapshot/SnapshotOptions.h"

namespace cdb {

struct SnapshotSummary {
  std::vector<std::filesystem::path> pictures;  // PNGs written, each with its .json
  std::optional<std::filesystem::path> animation;
  // Of the last picture.
  int width = 0, height = 0;
  std::optional<std::size_t> sets;  // with a culling strategy
  std::size_t collidingPairs = 0;
};

// Throws InputError for bad options or input (before anything is simulated where it can be
// known then), RunError when drawing or writing fails. Nothing partial is left at the output
// paths: each file is written under a temporary name and renamed.
SnapshotSummary runSnapshot(const SnapshotOptions& options);

}  // namespace cdb
