// libFuzzer target: see FuzzEntries.h.
#include <cstddef>
#include <cstdint>

#include "fuzz/FuzzEntries.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  cdb::fuzz::recording(data, size);
  return 0;
}
