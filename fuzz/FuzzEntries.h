#pragma once
// What each fuzz target does with one input, shared by the libFuzzer targets (fuzz_*.cpp) and the
// regression test that replays fuzz/regressions/ and fuzz/corpus/ in every build. A reader may
// refuse its input only with InputError (a one-line message); any other exception escapes, and
// libFuzzer reports it as a crash like a sanitizer finding.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "core/Errors.h"
#include "scenes/ConfigLoader.h"
#include "scenes/MeshLoader.h"
#include "scenes/PoseRecording.h"

namespace cdb::fuzz {

// YAML text -> scenario config.
inline void config(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    (void)loadScenarioConfigFromText(text, "fuzz.yaml");
  } catch (const InputError&) {
  }
  // The command line's integer lists take the same untrusted text.
  if (size <= 256) {
    try {
      (void)parseIntList(text);
    } catch (const InputError&) {
    }
  }
}

// The formats the asset path finds by stem; the first byte picks the importer, as the file
// extension does, so that the fuzzer explores both parsers rather than assimp's format guessing.
inline constexpr const char* kMeshFormats[] = {"ply", "obj"};

// First byte (format) + mesh file bytes -> loaded, normalised mesh.
inline void mesh(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return;
  const char* format = kMeshFormats[data[0] % 2];
  const auto bytes = std::as_bytes(std::span<const std::uint8_t>(data + 1, size - 1));
  try {
    LoadedMesh loaded = loadMeshFromMemory(bytes, format, std::string("fuzz.") + format);
    normaliseMesh(loaded.mesh, 1.0);
  } catch (const InputError&) {
  }
}

// Pose recording bytes -> recording.
inline void recording(const std::uint8_t* data, std::size_t size) {
  try {
    const PoseRecording r = readPoseRecordingFromBytes(
        std::span(reinterpret_cast<const char*>(data), size), "fuzz.poses");
    for (std::uint32_t f = 0; f < r.frameCount(); ++f) (void)r.frame(f);
  } catch (const InputError&) {
  }
}

}  // namespace cdb::fuzz
