#pragma once
// The charting library embedded in every report (uPlot, MIT licence, from the npm registry).
// Defined in a source file that CMake generates from the installed package (cmake/ReportAssets.cmake);
// all empty when the build has no report assets (MACHDYN_REPORT=OFF).
#include <string_view>

namespace machdyn::report::assets {
extern const std::string_view kUplotJs;       ///< dist/uPlot.iife.min.js
extern const std::string_view kUplotCss;      ///< dist/uPlot.min.css
extern const std::string_view kUplotVersion;  ///< e.g. "1.6.32"
}  // namespace machdyn::report::assets
