#pragma once
// A pass over a PLY file's body that checks, before assimp reads it, that every element the header
// declares fits in the bytes that follow: assimp sizes its arrays from the counts in the file, so
// a corrupt count in a few hundred bytes makes it allocate and clear gigabytes.
#include <string>
#include <string_view>

namespace cdb {

// `text` is the whole file and `bodyStart` the offset just past the header's end_header line.
// Throws InputError naming `name`, the element and what did not fit. A header this check does not
// understand (an unknown format or type) is left to assimp.
void checkPlyBodyBounds(std::string_view text, std::size_t bodyStart, const std::string& name);

}  // namespace cdb
