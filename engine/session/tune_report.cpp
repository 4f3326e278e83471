// report.html of a tune (session/tune.h): one page that reads offline.
#include "session/image_io.h"
#include "session/report_html.h"
#include "session/tune.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace tl::session {

namespace fs = std::filesystem;

namespace {

double value(const nlohmann::json& j) { return j.is_number() ? j.get<double>() : std::nan(""); }

// Frame time over the baseline's (x) against the error (y), each final point with its interval
// from the reference's noise; the front joined, the budgets as vertical lines, the chosen
// points ringed.
std::string frontPlot(const nlohmann::json& t) {
  const double W = 640, H = 360, left = 70, bottom = 44, top = 20, right = 20;
  double maxX = 1.2, maxY = 1e-9;
  auto consider = [&](const nlohmann::json& p) {
    maxX = std::max(maxX, value(p["timeRatio"]));
    if (std::isfinite(value(p["error"]["high"]))) maxY = std::max(maxY, value(p["error"]["high"]));
  };
  for (const auto& p : t["final"]) consider(p);
  consider(t["baseline"]);
  for (const auto& b : t["budgets"]) maxX = std::max(maxX, value(b["limitRatio"]));
  maxX *= 1.1, maxY *= 1.1;
  auto X = [&](double v) { return left + v / maxX * (W - left - right); };
  auto Y = [&](double v) { return H - bottom - std::max(0.0, v) / maxY * (H - bottom - top); };
  std::string svg = fmt::format("<svg width='{}' height='{}' xmlns='http://www.w3.org/2000/svg' font-size='12' "
                                "font-family='sans-serif'><rect width='100%' height='100%' fill='white'/>", W, H);
  svg += fmt::format("<line x1='{0}' y1='{1}' x2='{2}' y2='{1}' stroke='#888'/><line x1='{0}' y1='{1}' x2='{0}' y2='{3}' stroke='#888'/>",
                     left, H - bottom, W - right, top);
  const std::string baseline = t["plan"]["baseline"];
  svg += fmt::format("<text x='{}' y='{}' text-anchor='middle'>GPU frame time / {}'s (same run)</text>", (left + W - right) / 2,
                     H - 8, htmlEscape(baseline));
  svg += fmt::format("<text x='14' y='{}' transform='rotate(-90 14 {})' text-anchor='middle'>{} (worst view), 95% interval</text>",
                     H / 2, H / 2, htmlEscape(t["plan"]["metric"]));
  for (int k = 0; k <= 4; ++k) {
    svg += fmt::format("<text x='{}' y='{}' text-anchor='middle' fill='#666'>{:.2f}</text>", X(maxX * k / 4), H - bottom + 16, maxX * k / 4);
    svg += fmt::format("<text x='{}' y='{}' text-anchor='end' fill='#666'>{:.3g}</text>", left - 6, Y(maxY * k / 4) + 4, maxY * k / 4);
  }
  for (const auto& b : t["budgets"])
    svg += fmt::format("<line x1='{0:.1f}' y1='{1}' x2='{0:.1f}' y2='{2}' stroke='#99c' stroke-dasharray='2 3'/>"
                       "<text x='{0:.1f}' y='{3}' fill='#669' text-anchor='middle'>{4}</text>",
                       X(value(b["limitRatio"])), H - bottom, top, top + 10, htmlEscape(b["budget"]));
  std::string front;
  for (const auto& p : t["front"]) front += fmt::format("{:.1f},{:.1f} ", X(value(p["timeRatio"])), Y(value(p["error"]["value"])));
  if (!front.empty()) svg += "<polyline fill='none' stroke='#d33' stroke-dasharray='4 3' points='" + front + "'/>";
  auto point = [&](const nlohmann::json& p, const char* colour, const std::string& label) {
    const double x = X(value(p["timeRatio"])), y = Y(value(p["error"]["value"]));
    if (!std::isfinite(x) || !std::isfinite(y)) return;
    svg += fmt::format("<line x1='{0:.1f}' y1='{1:.1f}' x2='{0:.1f}' y2='{2:.1f}' stroke='{3}'/>", x, Y(value(p["error"]["low"])),
                       Y(value(p["error"]["high"])), colour);
    svg += fmt::format("<circle cx='{:.1f}' cy='{:.1f}' r='4' fill='{}'/>", x, y, colour);
    if (!label.empty()) svg += fmt::format("<text x='{:.1f}' y='{:.1f}'>{}</text>", x + 7, y - 5, htmlEscape(label));
  };
  for (const auto& p : t["final"]) point(p, "#2a6", p["name"]);
  point(t["baseline"], "#36c", baseline);
  for (const auto& b : t["budgets"]) {
    svg += fmt::format("<circle cx='{:.1f}' cy='{:.1f}' r='8' fill='none' stroke='#d33' stroke-width='2'/>",
                       X(value(b["chosen"]["timeRatio"])), Y(value(b["chosen"]["error"]["value"])));
    if (b.value("met", false)) point(b["presetMeasured"], "#d33", b["preset"]);
  }
  return svg + "</svg>";
}

std::string figure(const nlohmann::json& e) {
  return fmt::format("{:.4g} [{:.4g}, {:.4g}]", value(e["value"]), value(e["low"]), value(e["high"]));
}

std::string overridesText(const nlohmann::json& o) {
  if (o.empty()) return "(the path's defaults)";
  std::string text;
  for (const auto& [k, v] : o.items()) text += fmt::format("{}{}={}", text.empty() ? "" : ", ", k, v.dump());
  return text;
}

// The image of a configuration measured at full size (the preset's last measurement: the
// features-together stage, else the features stage), and that measurement's reference and
// baseline.
std::string imagesOf(const fs::path& dir, const std::string& name, const std::string& baseline) {
  std::error_code ec;
  for (const char* stage : {"features-together", "features"}) {
    if (!fs::is_directory(dir / stage, ec)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(dir / stage, ec)) {
      if (entry.path().filename() != name + ".png") continue;
      const fs::path folder = entry.path().parent_path();
      std::string html = "<div class='images'>";
      for (const auto& [file, caption] : std::vector<std::pair<std::string, std::string>>{
               {"reference.png", "reference"}, {name + ".png", "the preset (" + name + ")"}, {baseline + ".png", baseline}})
        if (fs::exists(folder / file))
          html += fmt::format("<figure><img src='{}'><figcaption>{}</figcaption></figure>", pngDataUri(folder / file),
                              htmlEscape(caption));
      return html + "</div>";
    }
  }
  return "";
}

}  // namespace

void writeTuneReportHtml(const fs::path& file, const nlohmann::json& t, const fs::path& tuneDir) {
  const nlohmann::json& plan = t["plan"];
  const std::string baseline = plan["baseline"];
  std::string html =
      "<!doctype html><html><head><meta charset='utf-8'><title>twinlight tune</title><style>"
      "body{font-family:sans-serif;margin:2em;max-width:1100px}table{border-collapse:collapse}"
      "td,th{border:1px solid #ccc;padding:3px 8px;font-size:13px;text-align:left}"
      ".images{display:flex;gap:8px}.images img{width:320px;image-rendering:pixelated}</style></head><body>";
  html += fmt::format("<h1>Tune of the {} path</h1>", htmlEscape(plan["path"]));
  html += fmt::format("<p>{} configuration(s) drawn with seed {}, one in {} kept per rung over {} rung(s); the last at {}x{}, "
                      "{} frames. {} compare run(s), {} configuration measurement(s). Times are ratios to {}'s defaults "
                      "measured in the same run ({:.2f} ms at full size); errors are the worst view's {} with the "
                      "reference's noise taken out and its 95% interval.</p>",
                      plan["candidates"].get<uint32_t>(), plan["seed"].get<uint64_t>(), plan["keepOneIn"].get<uint32_t>(),
                      plan["rungs"].get<uint32_t>(), plan["size"][0].get<uint32_t>(), plan["size"][1].get<uint32_t>(),
                      plan["frames"].get<uint32_t>(), t["measurements"]["compareRuns"].get<size_t>(),
                      t["measurements"]["configurationsMeasured"].get<size_t>(), htmlEscape(baseline),
                      value(t["baselineMs"]), htmlEscape(plan["metric"]));
  const std::string plot = frontPlot(t);
  html += plot;
  writeTextFile(file.parent_path() / "front.svg", plot + "\n");  // the plot alone, for documents
  html += "<h2>Budgets</h2>";
  for (const auto& b : t["budgets"]) {
    html += fmt::format("<h3>{} (at most {:.2f}x {})</h3>", htmlEscape(b["budget"]), value(b["limitRatio"]), htmlEscape(baseline));
    const auto& c = b["chosen"];
    const auto& m = b["presetMeasured"];
    html += fmt::format("<p>Chosen: <b>{}</b>{}, {:.2f}x ({:.2f} ms), error {}: {}.</p>", htmlEscape(c["name"]),
                        b.value("chosenOverBudget", false) ? " (the cheapest point: none was within the budget)" : "",
                        value(c["timeRatio"]), value(c["frameMs"]), figure(c["error"]), htmlEscape(overridesText(c["overrides"])));
    if (b.value("met", false))
      html += fmt::format("<p>Preset <code>{}</code>: {:.2f}x, error {}; its settings: {}.</p>", htmlEscape(b["preset"]),
                          value(m["timeRatio"]), figure(m["error"]), htmlEscape(overridesText(b["overrides"])));
    else
      html += fmt::format("<p><b>Not met</b>: the cheapest measured ran at {:.2f}x.</p>", value(b["cheapestRatio"]));
    html += "<table><tr><th>feature</th><th>verdict</th><th>saves (ms)</th><th>error with</th><th>error without</th><th>off in the preset</th></tr>";
    for (const auto& f : b["features"])
      html += fmt::format("<tr><td>{}</td><td>{}</td><td>{:.2f}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
                          htmlEscape(f["setting"]), htmlEscape(f["verdict"]), value(f["savesMs"]), figure(f["errorWith"]),
                          figure(f["errorWithout"]), f["offInPreset"].get<bool>() ? "yes" : "no");
    html += "</table>";
    if (b.value("met", false)) html += imagesOf(tuneDir, m["name"], baseline);
  }
  html += "<h2>The front (full size)</h2><table><tr><th>configuration</th><th>time</th><th>ms</th><th>error</th><th>worst view</th><th>settings</th></tr>";
  for (const auto& p : t["front"])
    html += fmt::format("<tr><td>{}</td><td>{:.2f}x [{:.2f}, {:.2f}]</td><td>{:.2f}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
                        htmlEscape(p["name"]), value(p["timeRatio"]), value(p["timeRatioInterval"][0]),
                        value(p["timeRatioInterval"][1]), value(p["frameMs"]), figure(p["error"]), htmlEscape(p["worstView"]),
                        htmlEscape(overridesText(p["overrides"])));
  html += "</table><h2>Rungs</h2><table><tr><th>rung</th><th>size</th><th>frames</th><th>configurations</th></tr>";
  for (const auto& r : t["rungs"])
    html += fmt::format("<tr><td>{}</td><td>{}x{}</td><td>{}</td><td>{}</td></tr>", htmlEscape(r["stage"]),
                        r["width"].get<uint32_t>(), r["height"].get<uint32_t>(), r["frames"].get<uint32_t>(), r["points"].size());
  html += "</table></body></html>\n";
  writeTextFile(file, html);
}

}  // namespace tl::session
