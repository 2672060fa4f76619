// fmt's compiled part, once for all of heavytop. Debian ships fmt as a shared library and as
// headers; heavytop's programs load no libfmt.so (start-up, README "start-up") and, rather than
// every source compiling fmt's implementation as FMT_HEADER_ONLY would (about a fifth of the
// compile time of each file that formats), this one file compiles it from the installed
// headers into heavytop_core, and every other file includes fmt's declarations only.
#include <fmt/format-inl.h>

FMT_BEGIN_NAMESPACE
namespace detail {
// The instantiations fmt's own format.cc makes for char, which the declarations leave extern.
template auto dragonbox::to_decimal(float x) noexcept -> dragonbox::decimal_fp<float>;
template auto dragonbox::to_decimal(double x) noexcept -> dragonbox::decimal_fp<double>;
template locale_ref::locale_ref(const std::locale& loc);
template auto locale_ref::get<std::locale>() const -> std::locale;
template auto thousands_sep_impl(locale_ref) -> thousands_sep_result<char>;
template auto decimal_point_impl(locale_ref) -> char;
template void buffer<char>::append(const char*, const char*);
template void vformat_to(buffer<char>&, string_view, basic_format_args<FMT_BUFFER_CONTEXT(char)>, locale_ref);
}  // namespace detail
FMT_END_NAMESPACE
