// report.html: one self-contained page (images inlined as data URIs, plots as inline SVG)
// that reads offline: the speed-against-error plot with its Pareto front, per-pass timing
// bars, each path's image beside the reference and its FLIP error map.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>

namespace tl::session {

// A PNG file as a data: URI, for a page that reads offline.
std::string pngDataUri(const std::filesystem::path& file);
// Text made safe inside HTML.
std::string htmlEscape(const std::string& text);

void writeReportHtml(const std::filesystem::path& file, const nlohmann::json& report, const std::filesystem::path& imageDir);

// A sweep's report.html (session/sweep.h): each configuration's mean figures over the views,
// their speed-against-error plot with its Pareto front, and a row per view linking its page.
void writeSweepReportHtml(const std::filesystem::path& file, const nlohmann::json& sweepReport);

}  // namespace tl::session
