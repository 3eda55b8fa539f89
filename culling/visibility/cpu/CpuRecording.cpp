#include "culling/visibility/cpu/CpuRecording.h"

namespace cdb {

void CpuRecording::close() {
  for (std::size_t i = 0; i < passes.size(); ++i)
    passes[i].endCommand = i + 1 < passes.size() ? passes[i + 1].firstCommand
                                                 : static_cast<std::uint32_t>(commands.size());
}

}  // namespace cdb
