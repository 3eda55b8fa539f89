#include "harness/common/BuildCommit.h"

#include "cdbench_build_commit.h"

namespace cdb {

std::string_view buildCommit() { return CDBENCH_BUILD_COMMIT; }

}  // namespace cdb
