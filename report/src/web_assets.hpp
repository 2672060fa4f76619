#pragma once
// Private to heavytop_report: the interactive page's files (three.js and uPlot bundled with the
// page script by esbuild from the npm packages in report/web/), embedded in the binary at build
// time so the report needs nothing at run time but the heavytop binary itself.

#include <cstddef>
#include <span>

namespace heavytop::report::detail {

/// One file the report writes beside report.html.
struct WebAsset {
  const char* name;            ///< file name in the report folder, e.g. "heavytop-report.js"
  const unsigned char* data;   ///< its bytes
  std::size_t size;            ///< bytes
};

/// The embedded files; empty when the build could not fetch the npm packages.
std::span<const WebAsset> web_assets();
/// Why web_assets() is empty (one sentence for the page), or nullptr when it is not.
const char* web_assets_missing();

}  // namespace heavytop::report::detail
