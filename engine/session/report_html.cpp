#include "session/report_html.h"

#include "session/image_io.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

namespace tl::session {
namespace {

std::string base64(const std::string& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    uint32_t v = (uint8_t(bytes[i]) << 16) | (uint8_t(bytes[i + 1]) << 8) | uint8_t(bytes[i + 2]);
    for (int s = 18; s >= 0; s -= 6) out += table[(v >> s) & 63];
  }
  if (i < bytes.size()) {
    uint32_t v = uint8_t(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= uint8_t(bytes[i + 1]) << 8;
    out += table[(v >> 18) & 63];
    out += table[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? table[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

}  // namespace

std::string pngDataUri(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return "data:image/png;base64," + base64(ss.str());
}

std::string htmlEscape(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
  return out;
}

namespace {

std::string number(const nlohmann::json& v, const char* format = "{:.4f}") {
  return v.is_number() ? fmt::format(fmt::runtime(format), v.get<double>()) : std::string("n/a");
}

// Frame time (x) against mean FLIP (y); the Pareto front joins the paths no other path
// beats on both.
std::string speedErrorPlot(const nlohmann::json& paths) {
  const double W = 560, H = 320, left = 60, bottom = 40, top = 20, right = 20;
  double maxX = 1e-6, maxY = 1e-6;
  for (auto& p : paths) {
    maxX = std::max(maxX, p["frameMs"].get<double>());
    if (p["FLIP"].is_number()) maxY = std::max(maxY, p["FLIP"].get<double>());
  }
  maxX *= 1.15, maxY *= 1.15;
  auto X = [&](double v) { return left + v / maxX * (W - left - right); };
  auto Y = [&](double v) { return H - bottom - v / maxY * (H - bottom - top); };
  std::string svg = fmt::format("<svg width='{}' height='{}' xmlns='http://www.w3.org/2000/svg' font-size='12'>", W, H);
  svg += fmt::format("<line x1='{0}' y1='{1}' x2='{2}' y2='{1}' stroke='#888'/><line x1='{0}' y1='{1}' x2='{0}' y2='{3}' stroke='#888'/>",
                     left, H - bottom, W - right, top);
  svg += fmt::format("<text x='{}' y='{}' text-anchor='middle'>GPU frame time (ms)</text>", (left + W - right) / 2, H - 8);
  svg += fmt::format("<text x='14' y='{}' transform='rotate(-90 14 {})' text-anchor='middle'>mean FLIP</text>", H / 2, H / 2);
  for (int t = 0; t <= 4; ++t) {
    svg += fmt::format("<text x='{}' y='{}' text-anchor='middle' fill='#666'>{:.1f}</text>", X(maxX * t / 4), H - bottom + 16, maxX * t / 4);
    svg += fmt::format("<text x='{}' y='{}' text-anchor='end' fill='#666'>{:.3f}</text>", left - 6, Y(maxY * t / 4) + 4, maxY * t / 4);
  }
  std::vector<std::pair<double, double>> pts;
  for (auto& p : paths)
    if (p["FLIP"].is_number()) pts.push_back({p["frameMs"].get<double>(), p["FLIP"].get<double>()});
  std::sort(pts.begin(), pts.end());
  std::string front;
  double best = 1e300;
  for (auto& [x, y] : pts)
    if (y < best) best = y, front += fmt::format("{:.1f},{:.1f} ", X(x), Y(y));
  if (!front.empty()) svg += "<polyline fill='none' stroke='#d33' stroke-dasharray='4 3' points='" + front + "'/>";
  for (auto& p : paths) {
    if (!p["FLIP"].is_number()) continue;
    double x = X(p["frameMs"].get<double>()), y = Y(p["FLIP"].get<double>());
    svg += fmt::format("<circle cx='{:.1f}' cy='{:.1f}' r='5' fill='#2a6'/><text x='{:.1f}' y='{:.1f}'>{}</text>", x, y, x + 8, y - 6,
                       htmlEscape(p["path"].get<std::string>()));
  }
  return svg + "</svg>";
}

std::string timingBars(const nlohmann::json& paths) {
  double worst = 1e-6;
  for (auto& p : paths) worst = std::max(worst, p["frameMs"].get<double>());
  std::string html;
  for (auto& p : paths) {
    html += fmt::format("<h4>{} — {:.2f} ms</h4>", htmlEscape(p["path"].get<std::string>()), p["frameMs"].get<double>());
    for (auto& [pass, ms] : p["passMs"].items())
      html += fmt::format("<div class='bar'><span style='width:{:.1f}%'></span>{} {:.2f} ms</div>", ms.get<double>() / worst * 100.0,
                          htmlEscape(pass), ms.get<double>());
  }
  return html;
}

const char* const kStyle = R"(<style>
body{font-family:sans-serif;margin:24px;color:#222;max-width:1200px}
table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:4px 10px;text-align:right}th{background:#f2f2f2}
td:first-child,th:first-child{text-align:left}
.bar{position:relative;height:18px;margin:2px 0;font-size:12px;line-height:18px;padding-left:4px}
.bar span{position:absolute;left:0;top:0;bottom:0;background:#9cd;z-index:-1}
.imgs{display:flex;gap:12px;flex-wrap:wrap}.imgs figure{margin:0}.imgs img{image-rendering:pixelated;width:256px}
.legend{height:12px;width:256px;background:linear-gradient(to right,#05051a,#590d73,#cc1a33,#fa800d,#fce533,#fff)}
</style>)";

// The gate's outcome: passed, FAILED, or undecided when a figure's interval holds its threshold
// and none is above (compare.cpp, evaluateGate).
std::string gateWord(const nlohmann::json& gate) {
  if (gate["passed"].get<bool>()) return "passed";
  return gate.value("decided", true) ? "FAILED" : "undecided (within the reference's noise)";
}

// The figures against the converged reference (the reference's noise taken out, a 95% interval
// each) and the rankings they support: "within noise" where two paths' intervals overlap.
std::string significanceSection(const nlohmann::json& r) {
  if (!r.contains("significance")) return "";
  const auto& sig = r["significance"];
  const auto& noise = r["reference"].value("noise", nlohmann::json::object());
  std::string html = "<h2>Against the converged reference</h2><p>Each figure with the reference's own noise taken out of "
                     "its expectation, and its 95% interval from that noise";
  if (noise.contains("relativeStdError"))
    html += fmt::format(" (the reference's relative standard error {}{})", number(noise["relativeStdError"]),
                        noise.contains("expectedRelMSE_norm")
                            ? fmt::format(", its own expected relMSE_norm against the converged image {}",
                                          number(noise["expectedRelMSE_norm"], "{:.5f}"))
                            : std::string());
  html += ". Two paths are ranked only where their intervals do not overlap; where they do, they are within noise of "
          "each other: more reference samples, not these figures, would tell them apart.</p><table><tr><th>path</th>";
  for (auto& m : sig["metrics"]) html += fmt::format("<th>{}</th>", htmlEscape(m.get<std::string>()));
  html += "</tr>";
  for (auto& p : r["paths"]) {
    if (!p.contains("significance")) continue;
    html += fmt::format("<tr><td>{}</td>", htmlEscape(p["path"].get<std::string>()));
    for (auto& m : sig["metrics"]) {
      const auto& f = p["significance"][m.get<std::string>()];
      html += fmt::format("<td>{} <small>[{}, {}]</small></td>", number(f["value"]), number(f["low"]), number(f["high"]));
    }
    html += "</tr>";
  }
  html += "</table>";
  if (sig.contains("rankings") && r["paths"].size() > 1) {
    html += "<p>Rankings (<b>&lt;</b> lower, significant; <b>~</b> within noise):</p><ul>";
    for (auto& m : sig["metrics"])
      if (sig["rankings"].contains(m.get<std::string>()))
        html += fmt::format("<li>{}: {}</li>", htmlEscape(m.get<std::string>()),
                            htmlEscape(sig["rankings"][m.get<std::string>()]["order"].get<std::string>()));
    html += "</ul>";
  }
  return html;
}

}  // namespace

void writeReportHtml(const std::filesystem::path& file, const nlohmann::json& r, const std::filesystem::path& dir) {
  std::string html = std::string("<!doctype html><html><head><meta charset='utf-8'><title>Twinlight compare</title>") + kStyle +
                     "</head><body>";
  html += fmt::format("<h1>Speed against error: {}</h1>", htmlEscape(r["scene"].get<std::string>()));
  const auto& ref = r["reference"];
  std::string reference;
  if (ref.value("source", "") == "file") {
    reference = fmt::format("Reference: the image {} (another renderer's, same camera and size)", htmlEscape(ref["file"].get<std::string>()));
  } else {
    const bool same = ref.value("scope", "full") == "same";
    reference = fmt::format("Reference: {} samples per pixel, {} scattering events{}{}; bounces: {}", ref["spp"].get<int>(),
                            ref["bounces"].get<int>(), same ? " (same scope as the real-time paths: direct + one bounce)" : "",
                            ref["cached"].get<bool>() ? " (reused from the cache)" : "", htmlEscape(ref.value("bouncePolicy", "")));
  }
  html += fmt::format("<p>{}×{} on {} ({}), Vulkan {}. {}. Materials: {}. Exposure {:.2f} EV.</p>", r["width"].get<int>(),
                      r["height"].get<int>(), htmlEscape(r["device"].get<std::string>()), htmlEscape(r["driver"].get<std::string>()),
                      r["vulkan"].get<std::string>(), reference, htmlEscape(ref.value("materials", "authored")),
                      r["exposureEV"].get<double>());
  if (r.contains("gate")) {
    const auto& g = r["gate"];
    std::string limits;
    for (auto& [m, v] : g["failAbove"].items()) limits += fmt::format("{}{} ≤ {}", limits.empty() ? "" : ", ", htmlEscape(m), v.get<double>());
    html += fmt::format("<p><b>Regression gate {}</b> ({}).</p>", gateWord(g), limits);
    if (!g["failures"].empty()) {
      html += "<table><tr><th>path</th><th>metric</th><th>value</th><th>threshold</th></tr>";
      for (auto& f : g["failures"])
        html += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>", htmlEscape(f["path"].get<std::string>()),
                            htmlEscape(f["metric"].get<std::string>()), number(f["value"]), f["threshold"].get<double>());
      html += "</table>";
    }
    if (g.contains("withinNoise") && !g["withinNoise"].empty()) {
      html += "<p>Within noise of their thresholds (the reference's noise cannot tell whether they pass: render it with "
              "more samples or a --reference-noise target):</p>";
      html += "<table><tr><th>path</th><th>metric</th><th>value</th><th>95% interval</th><th>threshold</th></tr>";
      for (auto& f : g["withinNoise"])
        html += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{} … {}</td><td>{}</td></tr>",
                            htmlEscape(f["path"].get<std::string>()), htmlEscape(f["metric"].get<std::string>()), number(f["value"]),
                            number(f["low"]), number(f["high"]), f["threshold"].get<double>());
      html += "</table>";
    }
  }
  html += significanceSection(r);
  html += "<h2>Error as rendered</h2><p>Linear radiance as each path rendered it; the display metrics at the report's "
          "exposure.</p>";
  html += "<table><tr><th>path</th><th>GPU ms</th><th>relMSE</th><th>RMSE</th><th>PSNR dB</th><th>SSIM</th><th>FLIP</th><th>HDR-FLIP</th></tr>";
  for (auto& p : r["paths"])
    html += fmt::format("<tr><td>{}</td><td>{:.2f}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
                        htmlEscape(p["path"].get<std::string>()), p["frameMs"].get<double>(), number(p["relMSE"]),
                        number(p["RMSE"]), number(p["PSNR"], "{:.2f}"), number(p["SSIM"]), number(p["FLIP"]),
                        number(p["HDR-FLIP"]));
  html += "</table>";
  html += fmt::format("<h2>Error exposure-normalised</h2><p>Both images scaled by {:.4g} so the reference's mean luminance "
                      "({:.4g}) becomes 0.18: a dark scene's figures mean what a bright one's do.</p>",
                      ref["normalisation"].get<double>(), ref["meanLuminance"].get<double>());
  html += "<table><tr><th>path</th><th>relMSE_norm</th><th>RMSE_norm</th><th>FLIP_norm</th></tr>";
  for (auto& p : r["paths"])
    html += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>", htmlEscape(p["path"].get<std::string>()),
                        number(p["relMSE_norm"]), number(p["RMSE_norm"]), number(p["FLIP_norm"]));
  html += "</table>";
  html += "<h2>Error per stage</h2><p>What the composite multiplied, against the reference's own estimate of the same "
          "quantity at the primary hit, over surface pixels: ambient occlusion and the diffuse irradiance (sky and bounce "
          "light; the sun is added separately).</p>";
  html += "<table><tr><th>path</th><th>AO mean abs error</th><th>AO RMSE</th><th>irradiance relMSE</th><th>irradiance RMSE</th></tr>";
  for (auto& p : r["paths"]) {
    if (!p.contains("stages") || !p["stages"].contains("ao")) continue;
    const auto& st = p["stages"];
    html += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>", htmlEscape(p["path"].get<std::string>()),
                        number(st["ao"]["meanAbsError"]), number(st["ao"]["RMSE"]), number(st["irradiance"]["relMSE"]),
                        number(st["irradiance"]["RMSE"]));
  }
  html += "</table>";
  if (r["reference"].contains("byDepth")) {
    // Per bounce: each path's captured share of each depth group (docs/accuracy.md).
    html += "<h2>Per bounce</h2><p>The share of each depth group of the reference's light a path holds (in each 8×8 "
            "tile its light is credited to the groups in depth order), and the light beyond the reference's.</p>"
            "<table><tr><th>path</th>";
    for (auto& g : r["reference"]["byDepth"]["groups"])
      html += fmt::format("<th>{} ({} of the reference)</th>", htmlEscape(g["group"].get<std::string>()), number(g["shareOfReference"]));
    html += "<th>excess</th><th>in words</th></tr>";
    for (auto& p : r["paths"]) {
      if (!p.contains("bounces") || !p["bounces"].contains("groups")) continue;
      html += fmt::format("<tr><td>{}</td>", htmlEscape(p["path"].get<std::string>()));
      for (auto& g : p["bounces"]["groups"]) html += fmt::format("<td>{}</td>", number(g["captured"]));
      html += fmt::format("<td>{}</td><td>{}</td></tr>", number(p["bounces"]["excess"]),
                          htmlEscape(p["bounces"]["summary"].get<std::string>()));
    }
    html += "</table>";
  }
  if (r["reference"].contains("byLobe")) {
    // Per lobe: what the surfaces reflect through their diffuse layer and their specular lobes.
    const auto& lobes = r["reference"]["byLobe"];
    html += fmt::format(
        "<h2>Per lobe</h2><p>The share of the light the surfaces the camera sees reflect through their diffuse "
        "layer ({} of the reference) and through their specular lobes (highlights and reflections, {}) that a "
        "path holds, and each lobe's relMSE_norm.</p><table><tr><th>path</th><th>diffuse</th><th>specular</th>"
        "<th>diffuse relMSE_norm</th><th>specular relMSE_norm</th><th>in words</th></tr>",
        number(lobes["diffuseShare"]), number(lobes["specularShare"]));
    for (auto& p : r["paths"]) {
      if (!p.contains("lobes") || !p["lobes"].contains("specular")) continue;
      const auto& l = p["lobes"];
      html += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
                          htmlEscape(p["path"].get<std::string>()), number(l["diffuse"]["captured"]),
                          number(l["specular"]["captured"]), number(l["diffuse"]["relMSE_norm"]),
                          number(l["specular"]["relMSE_norm"]), htmlEscape(l["summary"].get<std::string>()));
    }
    html += "</table>";
  }
  html += "<h2>Speed against error</h2>" + speedErrorPlot(r["paths"]);
  html += "<h2>Where the time goes</h2>" + timingBars(r["paths"]);
  html += "<h2>Images and FLIP error maps</h2><div class='imgs'>";
  html += fmt::format("<figure><img src='{}'><figcaption>reference</figcaption></figure>", pngDataUri(dir / "reference.png"));
  for (auto& p : r["paths"]) {
    html += fmt::format("<figure><img src='{}'><figcaption>{}</figcaption></figure>", pngDataUri(dir / p["image"].get<std::string>()),
                        htmlEscape(p["path"].get<std::string>()));
    html += fmt::format("<figure><img src='{}'><figcaption>{} — FLIP error</figcaption></figure>",
                        pngDataUri(dir / p["flipMap"].get<std::string>()), htmlEscape(p["path"].get<std::string>()));
  }
  html += "</div><p>FLIP error 0 <span class='legend' style='display:inline-block'></span> 1</p>";
  html += "<h2>Irradiance error maps</h2><div class='imgs'>";
  for (auto& p : r["paths"])
    if (p.contains("stages") && p["stages"].contains("irradianceMap"))
      html += fmt::format("<figure><img src='{}'><figcaption>{} — irradiance relMSE</figcaption></figure>",
                          pngDataUri(dir / p["stages"]["irradianceMap"].get<std::string>()), htmlEscape(p["path"].get<std::string>()));
  html += "</div><p>per-pixel relMSE of the diffuse irradiance 0 <span class='legend' style='display:inline-block'></span> 1</p>";
  html += "<h2>Metrics</h2><ul>";
  for (auto& [k, v] : r["metrics"].items()) html += fmt::format("<li><b>{}</b>: {}</li>", htmlEscape(k), htmlEscape(v.get<std::string>()));
  html += "</ul><p>Every figure is also in report.json beside this page.</p></body></html>\n";
  writeTextFile(file, html);
}

void writeSweepReportHtml(const std::filesystem::path& file, const nlohmann::json& r) {
  std::string html = std::string("<!doctype html><html><head><meta charset='utf-8'><title>Twinlight compare sweep</title>") +
                     kStyle + "</head><body>";
  const auto& views = r["views"];
  std::set<std::string> scenes;
  for (const auto& v : views) scenes.insert(v["scene"].get<std::string>());
  html += fmt::format("<h1>Speed against error: {} view(s) of {} scene(s)</h1>", views.size(), scenes.size());
  html += fmt::format("<p>Each configuration's figures are means over the views; every view has its own reference and "
                      "its own page. The reference: {} samples per pixel, scope {}.</p>",
                      r["grid"]["referenceSpp"].get<int>(), htmlEscape(r["grid"]["scope"].get<std::string>()));
  if (r.contains("gate")) {
    const auto& g = r["gate"];
    html += fmt::format("<p><b>Regression gate {}</b>: {} figure(s) above their thresholds, {} within the reference's "
                        "noise of them.</p>",
                        gateWord(g), g["failures"].size(), g.value("withinNoise", nlohmann::json::array()).size());
    if (!g["failures"].empty()) {
      html += "<table><tr><th>scene</th><th>camera</th><th>path</th><th>metric</th><th>value</th><th>threshold</th></tr>";
      for (auto& f : g["failures"])
        html += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
                            htmlEscape(f["scene"].get<std::string>()), htmlEscape(f["camera"].get<std::string>()),
                            htmlEscape(f["path"].get<std::string>()), htmlEscape(f["metric"].get<std::string>()), number(f["value"]),
                            f["threshold"].get<double>());
      html += "</table>";
    }
  }
  html += "<h2>Configurations (means over the views)</h2><table><tr><th>configuration</th><th>views</th><th>GPU ms</th>"
          "<th>relMSE</th><th>FLIP</th><th>HDR-FLIP</th><th>relMSE_norm</th><th>FLIP_norm</th></tr>";
  for (auto& c : r["configurations"])
    html += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
                        htmlEscape(c["path"].get<std::string>()), c["views"].get<int>(), number(c["frameMs"], "{:.2f}"),
                        number(c["relMSE"]), number(c["FLIP"]), number(c["HDR-FLIP"]), number(c["relMSE_norm"]),
                        number(c["FLIP_norm"]));
  html += "</table><h2>Speed against error</h2>";
  nlohmann::json plotted = nlohmann::json::array();  // the plot needs a frame time for every point
  for (auto& c : r["configurations"])
    if (c["frameMs"].is_number()) plotted.push_back(c);
  html += speedErrorPlot(plotted);
  html += "<h2>Views</h2><table><tr><th>scene</th><th>camera</th><th>device</th>";
  for (auto& c : r["configurations"]) html += fmt::format("<th>{} FLIP</th>", htmlEscape(c["path"].get<std::string>()));
  html += "</tr>";
  for (const auto& v : views) {
    const std::string camera = v["camera"].get<std::string>();
    html += fmt::format("<tr><td><a href='{}'>{}</a></td><td>{}</td><td>{}</td>", htmlEscape(v["html"].get<std::string>()),
                        htmlEscape(v["scene"].get<std::string>()), htmlEscape(camera.empty() ? "(as given)" : camera),
                        htmlEscape(v["device"].get<std::string>()));
    for (auto& c : r["configurations"]) {
      std::string flip = "n/a";
      for (auto& p : v["paths"])
        if (p["path"] == c["path"]) flip = number(p["FLIP"]);
      html += "<td>" + flip + "</td>";
    }
    html += "</tr>";
  }
  html += "</table><p>Every figure is also in report.json beside this page.</p></body></html>\n";
  writeTextFile(file, html);
}

}  // namespace tl::session
