// The Buffers panel (F2, View > Buffers): every resource of the compiled graph grouped by
// the pass that writes it, with format, size, memory and lifetime; the selected one is
// shown in the viewport through the viewer's controls, with a histogram and a pixel probe
// that shows the stored values and what they mean (the resource's declared decoder).
#include "buffer_panel.h"

#include "editor_app.h"
#include "ui_helpers.h"
#include "gpu/formats.h"
#include "shared/display.h"

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <iterator>

namespace tl::editor {
namespace {

std::string bytesText(VkDeviceSize b) {
  if (b >= (VkDeviceSize(1) << 20)) return fmt::format("{:.1f} MB", double(b) / double(1 << 20));
  if (b >= 1024) return fmt::format("{:.1f} KB", double(b) / 1024.0);
  return fmt::format("{} B", b);
}

std::string extentText(const graph::ResourceDesc& d) {
  if (d.type == graph::ResourceType::Buffer) return "buffer";
  std::string s = d.extent.depth > 1 ? fmt::format("{}x{}x{}", d.extent.width, d.extent.height, d.extent.depth)
                                     : fmt::format("{}x{}", d.extent.width, d.extent.height);
  if (d.mipLevels > 1) s += fmt::format(" ({} mips)", d.mipLevels);
  return s;
}

void resourceTable(EditorApp& app) {
  const auto& resources = app.session().resources();
  const auto& timings = app.session().timings();
  // Passes in execution order, then imported and previous-frame resources.
  std::vector<std::string> groups;
  for (const auto& t : timings) groups.push_back(t.pass);
  for (const auto& r : resources)
    if (std::find(groups.begin(), groups.end(), r.writer) == groups.end()) groups.push_back(r.writer);
  VkDeviceSize total = 0;
  for (const auto& r : resources) total += r.bytes;
  ImGui::TextDisabled("%zu resources, %zu passes, %s", resources.size(), timings.size(), bytesText(total).c_str());

  const ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY | ImGuiTableFlags_BordersInnerV;
  if (!ImGui::BeginTable("resources", 4, flags, ImVec2(0, 220))) return;
  ImGui::TableSetupScrollFreeze(0, 1);
  ImGui::TableSetupColumn("resource", ImGuiTableColumnFlags_WidthStretch);
  ImGui::TableSetupColumn("format", ImGuiTableColumnFlags_WidthFixed, 70.0f);
  ImGui::TableSetupColumn("size", ImGuiTableColumnFlags_WidthFixed, 90.0f);
  ImGui::TableSetupColumn("memory", ImGuiTableColumnFlags_WidthFixed, 62.0f);
  ImGui::TableHeadersRow();
  for (const std::string& group : groups) {
    ImGui::TableNextRow();
    ImGui::TableSetColumnIndex(0);
    ImGui::TextDisabled("%s", group.c_str());
    for (const auto& r : resources) {
      if (r.writer != group) continue;
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      const bool image = r.desc.type == graph::ResourceType::Image;
      const bool selected = app.viewer().resource == r.name;
      ImGui::Indent(10.0f);
      if (ImGui::Selectable(fmt::format("{}##res", r.name).c_str(), selected, ImGuiSelectableFlags_SpanAllColumns) && image)
        app.pinPreview(selected ? "" : r.name);
      trackItem("buffers." + r.name);
      ImGui::Unindent(10.0f);
      if (ImGui::IsItemHovered()) {
        std::string life = r.firstUse == graph::kNone ? "not used"
                                                      : fmt::format("passes {}..{} of the frame", r.firstUse, r.lastUse);
        ImGui::SetTooltip("%s\n%s\nwritten by %s; %s%s%s%s%s", r.name.c_str(), r.desc.description.c_str(), r.writer.c_str(),
                          life.c_str(), r.persistent ? "; persistent (kept across frames)" : "",
                          r.imported ? "; imported" : "", r.aliased ? "; aliased memory" : "",
                          r.desc.decoder.empty() ? "" : ("\ndecoded as: " + r.desc.decoder).c_str());
      }
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(image ? gpu::formatInfo(r.desc.format).name : "-");
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(extentText(r.desc).c_str());
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(bytesText(r.bytes).c_str());
    }
  }
  ImGui::EndTable();
}

// A horizontal bar of the false-colour ramp with the range's ends (and their unit).
void falseColourLegend(float lo, float hi, const std::string& unit = {}) {
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 p = ImGui::GetCursorScreenPos();
  const float w = ImGui::GetContentRegionAvail().x, h = 12.0f;
  const int steps = 48;
  for (int i = 0; i < steps; ++i) {
    glm::vec3 a = shared::tlDisplayFalseColour(float(i) / steps), b = shared::tlDisplayFalseColour(float(i + 1) / steps);
    dl->AddRectFilledMultiColor(ImVec2(p.x + w * i / steps, p.y), ImVec2(p.x + w * (i + 1) / steps, p.y + h),
                                ImGui::GetColorU32(ImVec4(a.r, a.g, a.b, 1)), ImGui::GetColorU32(ImVec4(b.r, b.g, b.b, 1)),
                                ImGui::GetColorU32(ImVec4(b.r, b.g, b.b, 1)), ImGui::GetColorU32(ImVec4(a.r, a.g, a.b, 1)));
  }
  ImGui::Dummy(ImVec2(w, h));
  const std::string suffix = unit.empty() ? "" : " " + unit;
  ImGui::Text("%.4g%s", lo, suffix.c_str());
  const std::string right = fmt::format("{:.4g}{}", hi, suffix);
  ImGui::SameLine(std::max(0.0f, w - ImGui::CalcTextSize(right.c_str()).x));
  ImGui::TextUnformatted(right.c_str());
}

// A horizontal black-to-white bar with its ends' captions (values shown as the grey level).
void greyLegend(const char* left, const char* right) {
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 p = ImGui::GetCursorScreenPos();
  const float w = ImGui::GetContentRegionAvail().x, h = 12.0f;
  dl->AddRectFilledMultiColor(p, ImVec2(p.x + w, p.y + h), IM_COL32(0, 0, 0, 255), IM_COL32(255, 255, 255, 255),
                              IM_COL32(255, 255, 255, 255), IM_COL32(0, 0, 0, 255));
  ImGui::Dummy(ImVec2(w, h));
  ImGui::TextUnformatted(left);
  ImGui::SameLine(std::max(0.0f, w - ImGui::CalcTextSize(right).x));
  ImGui::TextUnformatted(right);
}

// The texel under the mouse when it is over the viewport.
std::optional<glm::uvec3> hoveredTexel(EditorApp& app, const graph::Readback& r) {
  const ImVec2 m = ImGui::GetIO().MousePos;
  const glm::vec2 uv = (glm::vec2(m.x, m.y) - app.viewportMin()) / app.viewportSize();
  if (uv.x < 0.0f || uv.y < 0.0f || uv.x >= 1.0f || uv.y >= 1.0f || r.extent.width == 0) return std::nullopt;
  const glm::vec4 w = viewerWindow(app.viewer());
  const glm::vec2 s = glm::vec2(w) + uv * glm::vec2(w.z, w.w);
  if (s.x < 0.0f || s.y < 0.0f || s.x >= 1.0f || s.y >= 1.0f) return std::nullopt;
  return glm::uvec3(uint32_t(s.x * r.extent.width), uint32_t(s.y * r.extent.height), app.viewer().slice);
}

void probe(EditorApp& app, const graph::ResourceDesc& desc) {
  ViewerState& v = app.viewer();
  auto it = v.readbacks.find(v.resource);
  if (it == v.readbacks.end()) return;
  if (auto t = hoveredTexel(app, it->second)) v.probe = t;
  if (!v.probe) {
    ImGui::TextDisabled("Probe: hover the viewport");
    return;
  }
  const glm::uvec3 t = *v.probe;
  ImGui::Text("Probe: texel %u, %u%s", t.x, t.y, it->second.extent.depth > 1 ? fmt::format(", slice {}", t.z).c_str() : "");
  const ProbeLines lines = probeTexel(v, desc.decoder, t, app.session().decodingScene()).value();
  for (auto& [label, value] : lines.raw) ImGui::Text("  %s = %s", label.c_str(), value.c_str());
  for (auto& [label, value] : lines.decoded) ImGui::Text("  %s: %s", label.c_str(), value.c_str());
}

// A swatch with a caption, on one line.
void swatch(const glm::vec3& c, const char* caption) {
  ImGui::ColorButton(caption, ImVec4(c.r, c.g, c.b, 1.0f), ImGuiColorEditFlags_NoTooltip, ImVec2(12, 12));
  ImGui::SameLine(0.0f, 4.0f);
  ImGui::TextUnformatted(caption);
}

// The legend of what the viewport shows for a meaning: the quantity, its scale and flat colours.
void meaningControls(EditorApp& app, const lighting::MeaningView& m) {
  ViewerState& v = app.viewer();
  ImGui::TextWrapped("%s%s: %s", m.quantity.c_str(), m.unit.empty() ? "" : fmt::format(" ({})", m.unit).c_str(),
                     m.legend.c_str());
  if (m.fitted) {
    ImGui::SetNextItemWidth(-110);
    ImGui::DragFloatRange2("range", &v.rangeMin, &v.rangeMax, std::max(1e-4f, (v.rangeMax - v.rangeMin) * 0.005f), 0.0f,
                           0.0f, "%.4g", "%.4g");
    ImGui::SameLine();
    if (ImGui::Button("Auto-fit")) v.autoFitPending = true;
  }
  if (m.falseColour) falseColourLegend(v.rangeMin, v.rangeMax, m.unit);
  if (m.meaning == shared::kDisplayMeaningHitDistance) {
    swatch(shared::tlDisplayMissColour(), "miss (sky)");
    ImGui::SameLine();
    swatch(shared::tlDisplayPendingColour(), "pending");
  } else if (m.meaning == shared::kDisplayMeaningOctNormal || m.meaning == shared::kDisplayMeaningHitNormal) {
    const struct {
      glm::vec3 n;
      const char* caption;
    } axes[] = {{{1, 0, 0}, "+X"}, {{-1, 0, 0}, "-X"}, {{0, 1, 0}, "+Y"}, {{0, -1, 0}, "-Y"}, {{0, 0, 1}, "+Z"}, {{0, 0, -1}, "-Z"}};
    for (size_t i = 0; i < std::size(axes); ++i) {
      if (i) ImGui::SameLine();
      swatch(axes[i].n * 0.5f + 0.5f, axes[i].caption);
    }
  } else if (m.meaning == shared::kDisplayMeaningAo) {
    greyLegend("0 occluded", "1 open");
    ImGui::Checkbox("NaN/neg/>1", &v.highlightInvalid);
    tooltip("a visibility outside 0..1 is wrong: NaN magenta, negative blue, above 1 yellow");
  } else if (m.meaning == shared::kDisplayMeaningShIrradiance) {
    ImGui::Checkbox("NaN/Inf/neg", &v.highlightInvalid);
    tooltip("negative irradiance (SH ringing) blue, NaN magenta, infinity yellow; negative SH coefficients are valid");
  }
}

void viewerControls(EditorApp& app) {
  ViewerState& v = app.viewer();
  const graph::PhysicalInfo* info = nullptr;
  for (const auto& r : app.session().resources())
    if (r.name == v.resource) info = &r;
  if (!info) {
    ImGui::TextDisabled("Select an image above to view it in the viewport.");
    return;
  }
  const gpu::FormatInfo fi = gpu::formatInfo(info->desc.format);
  const bool integer = fi.kind == gpu::TexelKind::Uint || fi.kind == gpu::TexelKind::Sint;
  ImGui::Text("%s  %s %s", v.resource.c_str(), fi.name, extentText(info->desc).c_str());
  ImGui::TextWrapped("%s", info->desc.description.c_str());
  if (ImGui::Button("Final image")) app.pinPreview("");
  ImGui::SameLine();
  ImGui::Checkbox("Live", &v.live);
  ImGui::SameLine();
  if (ImGui::Button("Refresh")) v.refresh = true;
  const auto meaning = lighting::meaningView(info->desc.decoder);
  const bool negativesValid = !lighting::negativesInvalid(info->desc.decoder, info->desc.format);
  if (meaning) {
    int shown = v.meaning ? 0 : 1;
    ImGui::RadioButton(meaning->quantity.c_str(), &shown, 0);
    trackItem("buffers.meaning");
    tooltip("what the buffer means (decoded on the GPU), with its legend");
    ImGui::SameLine();
    ImGui::RadioButton("stored values", &shown, 1);
    trackItem("buffers.raw");
    tooltip("the values as stored (channels, range, false colour)");
    if ((shown == 0) != v.meaning) v.meaning = shown == 0, v.autoFitPending = true;
  }
  if (meaning && v.meaning) {
    meaningControls(app, *meaning);
  } else if (!integer) {
    static const char* kChannels[] = {"RGB", "R", "G", "B", "A", "luminance"};
    int channel = int(v.channel);
    ImGui::SetNextItemWidth(110);
    if (ImGui::Combo("channel", &channel, kChannels, IM_ARRAYSIZE(kChannels))) v.channel = uint32_t(channel), v.autoFitPending = true;
    ImGui::SameLine();
    if (ImGui::Button("Auto-fit")) v.autoFitPending = true;
    ImGui::SetNextItemWidth(-60);
    ImGui::DragFloatRange2("range", &v.rangeMin, &v.rangeMax, std::max(1e-4f, (v.rangeMax - v.rangeMin) * 0.005f), 0.0f, 0.0f,
                           "%.4g", "%.4g");
    if (ImGui::Button("-1 EV")) v.rangeMax = v.rangeMin + (v.rangeMax - v.rangeMin) * 2.0f;
    ImGui::SameLine();
    if (ImGui::Button("+1 EV")) v.rangeMax = v.rangeMin + (v.rangeMax - v.rangeMin) * 0.5f;
    ImGui::SameLine();
    ImGui::BeginDisabled(v.channel == shared::kDisplayChannelRgb);
    ImGui::Checkbox("false colour", &v.falseColour);
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::Checkbox(negativesValid ? "NaN/Inf" : "NaN/Inf/neg", &v.highlightInvalid);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(negativesValid ? "magenta: NaN, yellow: infinity (negatives are valid data here)"
                                       : "magenta: NaN, yellow: infinity, blue: negative");
    if (v.falseColour && v.channel != shared::kDisplayChannelRgb) falseColourLegend(v.rangeMin, v.rangeMax);
  }
  if (info->desc.extent.depth > 1) {
    // The slider names the axis it walks and what the index is (a clipmap level and voxel).
    int slice = int(std::min(v.slice, info->desc.extent.depth - 1));
    const std::string label = lighting::sliceMeaning(info->desc.decoder, info->desc.extent, uint32_t(slice));
    ImGui::SetNextItemWidth(-60);
    if (ImGui::SliderInt("z slice", &slice, 0, int(info->desc.extent.depth) - 1, label.c_str())) v.slice = uint32_t(slice);
    trackItem("buffers.slice");
    tooltip("a 3D image is shown one z slice at a time, texels square (its true aspect)");
  }
  ImGui::SetNextItemWidth(120);
  ImGui::SliderFloat("zoom", &v.zoom, 1.0f, 256.0f, "%.1fx", ImGuiSliderFlags_Logarithmic);
  ImGui::SameLine();
  if (ImGui::Button("Reset view")) v.zoom = 1.0f, v.centre = glm::vec2(0.5f);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Ctrl + wheel over the viewport zooms around the cursor;\ntexel borders show from 8x.");

  // A/B against a kept copy.
  if (ImGui::Button("Keep as B")) v.keepCopy = true;
  ImGui::SameLine();
  ImGui::BeginDisabled(v.copyOf != v.resource);
  ImGui::Checkbox("show B", &v.showCopy);
  ImGui::EndDisabled();
  auto live = v.readbacks.find(v.resource);
  if (v.copyOf == v.resource && live != v.readbacks.end() && live->second.bytes.size() == v.copyReadback.bytes.size()) {
    auto a = live->second.texels(), b = v.copyReadback.texels();
    double sum = 0.0, worst = 0.0;
    for (size_t i = 0; i < a.size(); ++i) {
      const double d = std::abs(double(a[i]) - double(b[i]));
      if (std::isfinite(d)) sum += d, worst = std::max(worst, d);
    }
    ImGui::SameLine();
    ImGui::TextDisabled("A-B: mean |d| %.4g, max %.4g", a.empty() ? 0.0 : sum / double(a.size()), worst);
  }

  if (live != v.readbacks.end() && (meaning && v.meaning ? meaning->fitted : !integer)) {
    std::vector<float> values =
        meaning && v.meaning ? v.meaningValues : channelValues(live->second, v.channel, v.slice);
    std::vector<float> h = histogram(values, v.rangeMin, v.rangeMax, 64);
    size_t invalid = 0, negative = 0;
    for (float x : values) invalid += !std::isfinite(x), negative += x < 0.0f;
    ImGui::PlotHistogram("##histogram", h.data(), int(h.size()), 0,
                         fmt::format("{} texels, {} {}, {} negative{}", values.size(), invalid,
                                     meaning && v.meaning ? "without a value" : "NaN/Inf", negative,
                                     negativesValid && !(meaning && v.meaning) ? " (valid here)" : "")
                             .c_str(),
                         0.0f,
                         *std::max_element(h.begin(), h.end()) * 1.05f + 1e-6f, ImVec2(ImGui::GetContentRegionAvail().x, 70));
  }
  probe(app, info->desc);
}

}  // namespace

void buffersPanel(EditorApp& app, bool& open) {
  if (!open) return;
  placeToolPanel(app.panelLayout(), ToolPanel::Buffers);
  if (!ImGui::Begin("Buffers", &open)) {
    ImGui::End();
    return;
  }
  if (!app.session().hasScene() && !app.session().hasCapture()) {
    ImGui::TextDisabled("No scene or capture.");
    ImGui::End();
    return;
  }
  resourceTable(app);
  ImGui::Separator();
  viewerControls(app);
  ImGui::End();
}

}  // namespace tl::editor
