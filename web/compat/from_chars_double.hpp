#pragma once
/// \file
/// std::from_chars for double, for Emscripten's libc++ (before LLVM 20 it has the integer
/// overloads only): web/Makefile includes this in every file it compiles, so that the native
/// sources build for the page as they are. It takes what the standard's from_chars takes in the
/// general format: an optional '-', then decimal digits with an optional point and exponent, or
/// inf, infinity, nan; no leading white space, no '+', no hexadecimal ("0x1p3" reads as 0 and
/// stops at 'x'). A finite text whose value overflows to infinity or underflows to zero is
/// result_out_of_range with `value` unchanged, as libstdc++'s is.
#include <version>  // _LIBCPP_VERSION
#if defined(__EMSCRIPTEN__) && defined(_LIBCPP_VERSION) && _LIBCPP_VERSION < 200000
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string>

namespace std {
inline from_chars_result from_chars(const char* first, const char* last, double& value) {
  const char* p = first;
  if (p != last && *p == '-') ++p;
  if (p == last || !(isdigit(static_cast<unsigned char>(*p)) || *p == '.' || *p == 'i' || *p == 'I' || *p == 'n' || *p == 'N'))
    return {first, errc::invalid_argument};
  string copy(first, last);
  const size_t digits = static_cast<size_t>(p - first);
  if (copy.size() > digits + 1 && copy[digits] == '0' && (copy[digits + 1] == 'x' || copy[digits + 1] == 'X'))
    copy.resize(digits + 1);  // strtod would read hexadecimal
  errno = 0;
  char* stop = nullptr;
  const double v = strtod(copy.c_str(), &stop);
  if (stop == copy.c_str()) return {first, errc::invalid_argument};
  const char* end = first + (stop - copy.c_str());
  if (errno == ERANGE && (isinf(v) || v == 0.0)) return {end, errc::result_out_of_range};
  value = v;
  return {end, errc()};
}
}  // namespace std
#endif
