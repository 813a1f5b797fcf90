#pragma once
// GBL_ASAN is 1 when AddressSanitizer instruments this translation unit, whichever compiler: GCC
// defines __SANITIZE_ADDRESS__, clang 14 (the sanitizer build's, scripts/test-sanitizers.sh) only
// answers __has_feature(address_sanitizer).
#if defined(__SANITIZE_ADDRESS__)
#define GBL_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define GBL_ASAN 1
#endif
#endif
#ifndef GBL_ASAN
#define GBL_ASAN 0
#endif
