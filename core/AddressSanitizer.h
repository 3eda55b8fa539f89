#pragma once
// Whether this build runs under AddressSanitizer: GCC says so by __SANITIZE_ADDRESS__, clang by
// __has_feature(address_sanitizer).

namespace cdb {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kAddressSanitizer = true;
#else
inline constexpr bool kAddressSanitizer = false;
#endif
#else
inline constexpr bool kAddressSanitizer = false;
#endif

}  // namespace cdb
