#pragma once
// A PLY file read as the format defines it, checked, and written out again in the one form that
// assimp 5.2's PLY reader reads the same way.
//
// assimp reads a PLY its own way, and sizes its arrays from the counts it reads before it reads
// the data, so a file it misreads can make it allocate gigabytes from a few hundred bytes:
// - it takes the count of an element it does not know from the element's name ("element 7face 3"
//   asks for seven items, "element range_grid 9" for none), and keeps going when a property's
//   type is unknown, dropping that property and those after it;
// - it reads each item of an ASCII body from a line of its own, and stops a value at the first
//   character that does not belong to it;
// - it allocates the items of an element without properties without reading anything.
// So the header is rewritten from what was read ("ply", the format, the elements assimp knows:
// vertex, face, tristrips, edge, material, with their properties, "end_header"; comments and
// obj_info go), a binary body is kept as it is once it is known to hold what the header declares,
// and an ASCII body is written one item per line from its checked values.
#include <string>
#include <string_view>

namespace cdb {

// `text` is the whole file and `bodyStart` the offset just past the header's end_header line.
// Returns the file in the form above. Throws InputError naming `name`, the header line, element
// or value that does not fit the format, and what was expected.
std::string canonicalPly(std::string_view text, std::size_t bodyStart, const std::string& name);

}  // namespace cdb
