#pragma once
// The commit the binary was built from (cmake/BuildCommit.cmake): "+dirty" appended when tracked
// files differed from it, "unknown" when built outside a git checkout.
#include <string_view>

namespace cdb {

[[nodiscard]] std::string_view buildCommit();

}  // namespace cdb
