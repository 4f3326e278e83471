#include "compare_panel.h"

#include "editor_app.h"
#include "ui_helpers.h"

#include "shared/display.h"

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>

namespace tl::editor {
namespace {

// A combo of the lighting paths; unavailable ones are listed greyed with their reason.
bool pathCombo(const char* label, std::string& value, const std::vector<session::PathInfo>& paths) {
  bool changed = false;
  if (ImGui::BeginCombo(label, value.c_str())) {
    for (const auto& p : paths) {
      ImGui::BeginDisabled(!p.available);
      if (ImGui::Selectable(p.name.c_str(), p.name == value)) value = p.name, changed = true;
      ImGui::EndDisabled();
      if (!p.available) tooltip(p.unavailableReason.c_str());
    }
    ImGui::EndCombo();
  }
  return changed;
}

std::string figure(const std::optional<double>& v, const char* format) {
  return v ? fmt::format(fmt::runtime(format), *v) : std::string("—");
}

// Each side's relMSE as a bar with the reference's noise as a band at its end: a side's
// figure against a noisy reference holds about that much of the reference's own error, so
// its own lies within the band. Two bands that overlap cannot be ranked yet.
[[gnu::noinline]] void relMseBands(const std::vector<session::LiveError>& errors, const std::string& reference, double noise) {
  double top = noise;
  for (const auto& e : errors)
    if (e.relMse && e.path != reference) top = std::max(top, *e.relMse);
  if (!(top > 0.0)) return;
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
  ImGui::TextWrapped("relMSE, with the reference's noise as a band (the path's own error lies in it):");
  ImGui::PopStyleColor();
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const float labelWidth = 80.0f, height = ImGui::GetTextLineHeight();
  for (const auto& e : errors) {
    if (!e.relMse || e.path == reference) continue;
    ImGui::TextUnformatted(e.path.c_str());
    ImGui::SameLine(labelWidth);
    const ImVec2 p = ImGui::GetCursorScreenPos();
    const double r = *e.relMse, low = std::max(0.0, r - noise);
    // The bar takes what the figure beside it leaves, so the figure is never cut off.
    const std::string text = fmt::format("{:.4f} (own {:.4f}..{:.4f})", r, low, r);
    const float width = std::max(40.0f, ImGui::GetContentRegionAvail().x - ImGui::CalcTextSize(text.c_str()).x -
                                            2.0f * ImGui::GetStyle().ItemSpacing.x);
    auto x = [&](double v) { return p.x + float(v / top) * width; };
    dl->AddRectFilled(ImVec2(p.x, p.y + 2), ImVec2(x(low), p.y + height - 2), IM_COL32(90, 150, 230, 255));
    dl->AddRectFilled(ImVec2(x(low), p.y + 2), ImVec2(std::max(x(r), x(low) + 1.0f), p.y + height - 2), IM_COL32(90, 150, 230, 90));
    dl->AddRect(ImVec2(x(low), p.y + 1), ImVec2(std::max(x(r), x(low) + 1.0f), p.y + height - 1), IM_COL32(200, 200, 200, 200));
    ImGui::Dummy(ImVec2(width, height));
    ImGui::SameLine();
    ImGui::TextUnformatted(text.c_str());
  }
}

}  // namespace

void comparePanel(EditorApp& app) {
  if (!app.compareOpen()) return;
  placeToolPanel(app.panelLayout(), ToolPanel::Compare);
  if (!ImGui::Begin("Compare", &app.compareOpen())) {
    ImGui::End();
    return;
  }
  auto& session = app.session();
  auto& view = app.compareView();
  bool on = view.has_value();
  if (ImGui::Checkbox("Split the viewport", &on)) app.setCompare(on);
  ImGui::SameLine();
  ImGui::TextDisabled("(F3)");
  if (!view) {
    ImGui::TextWrapped("Shows two lighting paths at once, rendered in turn on the same camera, with their error against "
                       "the reference path tracer.");
    ImGui::End();
    return;
  }
  const auto paths = session.paths();
  pathCombo("left", view->left, paths);
  pathCombo("right", view->right, paths);
  int mode = view->difference ? 1 : 0;
  ImGui::RadioButton("wipe", &mode, 0);
  trackItem("compare.wipe");
  ImGui::SameLine();
  ImGui::RadioButton("difference", &mode, 1);
  trackItem("compare.difference");
  view->difference = mode == 1;
  if (view->difference) {
    ImGui::SliderFloat("scale", &view->differenceScale, 1.0f, 64.0f, "%.0fx", ImGuiSliderFlags_Logarithmic);
    tooltip("the top of the ramp is a display-value difference of 1/scale");
  } else {
    ImGui::SliderFloat("wipe", &view->wipe, 0.0f, 1.0f, "%.2f");
    tooltip("or drag the line in the viewport");
  }
  ImGui::Checkbox("FLIP (CPU, every 1.5 s)", &view->measureFlip);
  tooltip("measured on a worker thread: the figure is the last one finished, the viewport never waits for it");

  ImGui::Separator();
  const session::LiveCompare* live = session.liveCompare();
  if (!live) {
    ImGui::End();
    return;
  }
  if (live->referenceUnavailable()) {
    ImGui::TextWrapped("No live error: the reference needs ray tracing (%s).", live->referenceUnavailable()->c_str());
  } else {
    ImGui::Text("reference: %u samples per pixel", live->referenceSamples());
    tooltip("accumulates while the camera, projection, light, scene, geometry and its settings stay (the frame key); "
            "starts over when one of them changes");
    if (live->referenceRestarts() > 0) {
      ImGui::SameLine();
      const lighting::FrameParts cause = live->lastReferenceRestart();
      ImGui::TextDisabled("restarted %ux, last by %s", live->referenceRestarts(),
                          cause ? lighting::describeParts(cause).c_str() : "a reset or a resize");
    }
  }
  // The reference's own noise: until it is well below the gap between the sides, their
  // figures measure the reference as much as the paths (the ranking can still flip).
  const std::optional<double> noise = live->referenceUnavailable() ? std::nullopt : live->referenceNoise();
  const bool trusted = live->referenceTrusted();
  if (!live->referenceUnavailable()) {
    ImGui::Text("reference noise: relMSE %s", noise ? fmt::format("~{:.4f}", *noise).c_str() : "not known yet");
    tooltip("the reference's own error at its samples, estimated from two states of its accumulation; each side's "
            "relMSE holds about this much of it");
  }
  const ImVec4 grey = ImGui::GetStyle().Colors[ImGuiCol_TextDisabled];
  if (ImGui::BeginTable("compare.errors", 4, ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg)) {
    for (const char* h : {"path", "GPU ms", "relMSE", "FLIP"}) ImGui::TableSetupColumn(h);
    ImGui::TableNextRow(ImGuiTableRowFlags_Headers);
    const char* meanings[] = {"the lighting path", "the GPU time of its last frame",
                              "relative mean squared error of the radiance against the reference: lower is better; "
                              "0 = identical",
                              "perceived difference of the displayed images (NVIDIA FLIP, 0..1): lower is better; "
                              "0 = identical"};
    for (int c = 0; c < 4; ++c) {
      ImGui::TableSetColumnIndex(c);
      ImGui::TableHeader(ImGui::TableGetColumnName(c));
      tooltip(meanings[c]);
    }
    for (const auto& e : live->errors()) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(e.path.c_str());
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(fmt::format("{:.2f}", e.gpuMs).c_str());
      if (!trusted) ImGui::PushStyleColor(ImGuiCol_Text, grey);
      ImGui::TableNextColumn();
      if (e.path == app.session().referencePath()) {
        ImGui::TextUnformatted("0 (itself)");
      } else if (e.relMseAgainstConverged) {
        const auto& f = *e.relMseAgainstConverged;
        ImGui::TextUnformatted(fmt::format("{:.4f} [{:.4f}, {:.4f}]", f.value, f.low, f.high).c_str());
        tooltip(fmt::format("against the converged reference, the reference's noise taken out, with its 95% interval; "
                            "against the reference as rendered: {:.4f}", f.raw).c_str());
      } else {
        ImGui::TextUnformatted(figure(e.relMse, "{:.4f}").c_str());
        if (!trusted) tooltip("reference still converging: this figure is not yet the path's own");
      }
      ImGui::TableNextColumn();
      if (e.path != app.session().referencePath() && e.flipAgainstConverged) {
        const auto& f = *e.flipAgainstConverged;
        ImGui::TextUnformatted(fmt::format("{:.4f} [{:.4f}, {:.4f}]", f.value, f.low, f.high).c_str());
        tooltip(fmt::format("against the converged reference (simulation-extrapolation of the reference's noise), with "
                            "its 95% interval; against the reference as rendered: {:.4f}", f.raw).c_str());
      } else {
        ImGui::TextUnformatted(e.path == app.session().referencePath() ? "0" : figure(e.flip, "{:.4f}").c_str());
      }
      if (!trusted) ImGui::PopStyleColor();
    }
    ImGui::EndTable();
  }
  const auto errors = live->errors();
  // (A plain double, not `noise`: GCC 12 takes the optional's value as maybe uninitialised.)
  const double noiseValue = live->referenceUnavailable() ? -1.0 : live->referenceNoise().value_or(-1.0);
  if (noiseValue >= 0.0) relMseBands(errors, app.session().referencePath(), noiseValue);
  // The verdict: none until the two sides' intervals against the converged reference part
  // (LiveCompare::verdict); "within noise" while they overlap.
  const bool twoPaths = errors.size() == 2 && errors[0].path != app.session().referencePath() &&
                        errors[1].path != app.session().referencePath();
  if (!live->referenceUnavailable() && twoPaths) {
    const session::LiveVerdict verdict = live->verdict();
    if (verdict == session::LiveVerdict::LeftCloser || verdict == session::LiveVerdict::RightCloser) {
      const bool leftCloser = verdict == session::LiveVerdict::LeftCloser;
      const auto& closer = leftCloser ? errors[0] : errors[1];
      const auto& farther = leftCloser ? errors[1] : errors[0];
      const auto &a = *closer.relMseAgainstConverged, &b = *farther.relMseAgainstConverged;
      ImGui::TextWrapped("%s is closer to the converged reference: relMSE %.4f [%.4f, %.4f] against %s's %.4f [%.4f, %.4f]",
                         closer.path.c_str(), a.value, a.low, a.high, farther.path.c_str(), b.value, b.low, b.high);
      tooltip("the reference's noise taken out of both figures; the 95% intervals do not overlap");
    } else {
      ImGui::PushStyleColor(ImGuiCol_Text, grey);
      if (verdict == session::LiveVerdict::WithinNoise)
        ImGui::TextWrapped("within noise: %s and %s cannot be told apart at %u samples per pixel (their relMSE intervals "
                           "overlap); the verdict waits for the reference to converge",
                           errors[0].path.c_str(), errors[1].path.c_str(), live->referenceSamples());
      else
        ImGui::TextWrapped("no verdict yet: the reference needs %u samples per pixel before its noise is known",
                           session::LiveCompare::kMinVerdictSamples);
      ImGui::PopStyleColor();
    }
  } else if (!live->referenceUnavailable() && !trusted) {
    ImGui::PushStyleColor(ImGuiCol_Text, grey);
    ImGui::TextWrapped("reference still converging: the path's figure still holds the reference's own noise");
    ImGui::PopStyleColor();
  }
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
  const size_t turns = live->rotationLength();
  if (turns > 1)
    ImGui::TextWrapped("Each path renders every %s frame; its history, noise and timing are its own.",
                       turns == 2 ? "second" : "third");
  ImGui::PopStyleColor();
  ImGui::End();
}

void compareViewportOverlay(EditorApp& app) {
  const auto& view = app.compareView();
  if (!view || !app.session().hasScene()) return;
  const glm::vec2 min = app.viewportMin(), size = app.viewportSize();
  if (size.x < 1.0f || size.y < 1.0f) return;
  // Under the panels, over the engine image (the viewport window draws no background).
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  auto label = [&](ImVec2 at, const std::string& text) {
    ImVec2 extent = ImGui::CalcTextSize(text.c_str());
    draw->AddRectFilled(ImVec2(at.x - 4, at.y - 2), ImVec2(at.x + extent.x + 4, at.y + extent.y + 2), IM_COL32(0, 0, 0, 160), 3.0f);
    draw->AddText(at, IM_COL32(255, 255, 255, 255), text.c_str());
  };
  const float top = min.y + 8.0f;
  if (view->difference) {
    label(ImVec2(min.x + 8.0f, top), fmt::format("|{} - {}|", view->left, view->right));
    // The false-colour ramp the compare view uses, 0 .. 1/scale.
    const float x0 = min.x + 8.0f, y0 = top + 24.0f, width = 160.0f;
    for (int i = 0; i < 32; ++i) {
      glm::vec3 c = shared::tlDisplayFalseColour((i + 0.5f) / 32.0f);
      draw->AddRectFilled(ImVec2(x0 + width * i / 32.0f, y0), ImVec2(x0 + width * (i + 1) / 32.0f, y0 + 10.0f),
                          IM_COL32(int(c.r * 255), int(c.g * 255), int(c.b * 255), 255));
    }
    label(ImVec2(x0, y0 + 14.0f), fmt::format("0 .. {:.3f}", 1.0f / view->differenceScale));
    return;
  }
  const float split = min.x + view->wipe * size.x;
  label(ImVec2(std::max(min.x + 8.0f, split - 8.0f - ImGui::CalcTextSize(view->left.c_str()).x), top), view->left);
  label(ImVec2(std::min(split + 8.0f, min.x + size.x - 8.0f - ImGui::CalcTextSize(view->right.c_str()).x), top), view->right);
  // The handle the artist drags.
  draw->AddCircleFilled(ImVec2(split, min.y + size.y * 0.5f), 6.0f, IM_COL32(255, 255, 255, 220));
}

}  // namespace tl::editor
