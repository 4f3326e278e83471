#include "albedo_panels.h"

#include "column_panels.h"
#include "editor_app.h"
#include "ui_helpers.h"

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <filesystem>

namespace tl::editor {
namespace {

using albedo::AlbedoEntry;
using albedo::AlbedoSource;

// A view variance above this (a standard deviation of 0.1 between the views' mean albedo)
// marks an entry whose colour depends on where it is seen from.
constexpr float kHighViewVariance = 0.01f;

ImVec4 colour(const glm::vec3& c) { return ImVec4(c.r, c.g, c.b, 1.0f); }

void saveEdits(EditorApp& app) {
  try {
    app.session().albedo().save();
  } catch (const std::exception& e) {
    app.showError(e.what());
  }
}

void showView(EditorApp& app, const char* resource) {
  app.pinPreview(app.pinnedPreview() == resource ? "" : resource);
}

enum class Filter { All, Override, Baked, TextureAverage, Stale, Missing, HighVariance };
constexpr const char* kFilterNames[] = {"all", "override", "baked", "texture average", "stale", "missing (not baked)",
                                        "high view variance"};

bool passes(const AlbedoEntry& e, Filter f) {
  switch (f) {
    case Filter::All: return true;
    case Filter::Override: return e.source == AlbedoSource::Override;
    case Filter::Baked: return e.source == AlbedoSource::Baked;
    case Filter::TextureAverage: return e.source == AlbedoSource::TextureAverage;
    case Filter::Stale: return e.stale;
    case Filter::Missing: return !e.baked;
    case Filter::HighVariance: return e.baked && e.baked->viewVariance > kHighViewVariance;
  }
  return true;
}

// Re-applying and deleting orphans are edits like any other: Ctrl+Z undoes them, Save writes them.
void reapply(EditorApp& app, size_t orphan, uint32_t combination) {
  auto& lib = app.session().albedo();
  lib.reapplyOrphan(orphan, combination);
  app.notify(fmt::format("re-applied the override of {} to {} (key {}); Save writes it", lib.orphans()[orphan].label,
                         lib.entries()[combination].combination.label,
                         albedo::keyToHex(lib.entries()[combination].combination.key)));
}

// Overrides that reach no hit any more, with the colour they held, why, and what to do.
void orphanSection(EditorApp& app) {
  auto& lib = app.session().albedo();
  const size_t count = lib.orphanCount();
  if (count == 0) return;
  ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.75f, 0.3f, 1.0f));
  const bool open = ImGui::CollapsingHeader(fmt::format("Orphaned overrides ({})###orphans", count).c_str(),
                                            ImGuiTreeNodeFlags_DefaultOpen);
  ImGui::PopStyleColor();
  tooltip("Artist overrides whose mesh + material key is in no combination of this scene: the content\n"
      "changed after the edit (an export with another colour, UVs or geometry), or it is gone.\n"
      "They stay in the database until re-applied or deleted; Save keeps them.");
  if (!open) return;
  const auto selected = app.selected();
  const float height = std::min(170.0f, ImGui::GetTextLineHeightWithSpacing() * 6.5f * float(count) + 8.0f);
  ImGui::BeginChild("orphans", ImVec2(0, height), true);
  for (size_t i = 0; i < lib.orphans().size(); ++i) {
    const albedo::OrphanOverride& o = lib.orphans()[i];
    if (o.removed) continue;
    ImGui::PushID(int(i));
    ImGui::ColorButton("##lost", colour(o.rgb), 0, ImVec2(28, 28));
    ImGui::SameLine();
    ImGui::BeginGroup();
    ImGui::TextUnformatted(o.label.c_str());
    ImGui::TextDisabled("%.3f %.3f %.3f, key %s, %s", o.rgb.r, o.rgb.g, o.rgb.b, albedo::keyToHex(o.key).c_str(),
                        o.editedAt.empty() ? "never saved" : o.editedAt.c_str());
    ImGui::EndGroup();
    if (o.sameLabel) {
      if (ImGui::Button("Re-apply to the new key")) reapply(app, i, *o.sameLabel);
      tooltip(fmt::format("Override {} (the same mesh + material name, its content changed) with this colour.",
                          lib.entries()[*o.sameLabel].combination.label).c_str());
    }
    ImGui::BeginDisabled(!selected);
    if (ImGui::Button("Re-apply to selected") && selected) reapply(app, i, lib.combinationOf(*selected));
    ImGui::EndDisabled();
    tooltip(selected ? fmt::format("Override {} with this colour.", lib.entryOf(*selected).combination.label).c_str()
                     : "Select an instance to give its mesh + material this colour.");
    ImGui::SameLine();
    if (ImGui::Button("Delete")) lib.deleteOrphan(i);
    tooltip("Forget this override: the database drops it on Save (Ctrl+Z undoes).");
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextDisabled("%s", albedo::orphanReason(o).c_str());
    ImGui::PopTextWrapPos();
    ImGui::Separator();
    ImGui::PopID();
  }
  ImGui::EndChild();
}

}  // namespace

void albedoInspectorSection(EditorApp& app, uint32_t instance) {
  auto& lib = app.session().albedo();
  if (instance >= lib.instanceAlbedo().size()) return;
  const uint32_t c = lib.combinationOf(instance);
  const AlbedoEntry& e = lib.entries()[c];
  if (!ImGui::CollapsingHeader("Albedo (ray hits)", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::ColorButton("##resolved", colour(e.resolved), ImGuiColorEditFlags_NoTooltip, ImVec2(36, 36));
  ImGui::SameLine();
  ImGui::BeginGroup();
  ImGui::Text("%.3f %.3f %.3f  (linear)", e.resolved.r, e.resolved.g, e.resolved.b);
  ImGui::Text("source: %s", albedo::sourceName(e.source));
  ImGui::EndGroup();
  tooltip("What the RT path's rays read when they hit this instance (Metro: one pre-filtered albedo per\n"
      "mesh + material). Order: artist override > baked database entry > texture average.");
  ImGui::TextDisabled("key %s, %zu instance(s) share it", albedo::keyToHex(e.combination.key).c_str(),
                      e.combination.instances.size());
  if (e.baked)
    ImGui::Text("baked %.3f %.3f %.3f, coverage %.2f, view variance %.4f", e.baked->rgb.r, e.baked->rgb.g, e.baked->rgb.b,
                e.baked->coverage, e.baked->viewVariance);
  else
    ImGui::TextDisabled(e.stale ? "not baked: stale (content changed since the bake)" : "not baked");
  // An override made before this combination's content changed.
  for (size_t i = 0; i < lib.orphans().size(); ++i) {
    const albedo::OrphanOverride& o = lib.orphans()[i];
    if (o.removed || o.sameLabel != c) continue;
    ImGui::PushID(int(i));
    ImGui::ColorButton("##orphan", colour(o.rgb), 0, ImVec2(14, 14));
    ImGui::SameLine();
    if (ImGui::SmallButton("Re-apply")) reapply(app, i, c);
    tooltip(albedo::orphanReason(o).c_str());
    ImGui::SameLine();
    ImGui::TextDisabled("its override from before the change");
    ImGui::PopID();
  }
  ImGui::Text("texture average %.3f %.3f %.3f", e.textureAverage.r, e.textureAverage.g, e.textureAverage.b);

  glm::vec3 edit = e.override.value_or(e.resolved);
  if (ImGui::ColorEdit3("Override", &edit.x, ImGuiColorEditFlags_Float)) {
    // One undo step per drag: later changes of the same drag fold into the first.
    const bool continuing = ImGui::IsItemActive() && !ImGui::IsItemActivated() && e.override.has_value();
    lib.setOverride(c, edit, continuing);
  }
  tooltip("Writes an override for this mesh + material (every instance sharing it). Linear RGB.\n"
      "Changes the RT path's colour bleeding from the next frame. Ctrl+Z / Ctrl+Y undo and redo.");
  ImGui::BeginDisabled(!e.override);
  if (ImGui::Button("Clear override")) lib.clearOverride(c);
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(!lib.canUndo());
  if (ImGui::Button("Undo")) lib.undo();
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(!lib.canRedo());
  if (ImGui::Button("Redo")) lib.redo();
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(!lib.unsaved() || !lib.database());
  if (ImGui::Button(lib.unsaved() ? "Save*" : "Save")) saveEdits(app);
  ImGui::EndDisabled();
  tooltip(lib.database() ? "Write the overrides to the database (one transaction). Ctrl+S"
                     : "Open or create a database in the Albedo panel to save overrides.");

  if (ImGui::Button("Albedo view")) showView(app, "albedo.instance");
  tooltip("Viewport: the albedo rays read, per pixel (albedo.instance).");
  ImGui::SameLine();
  if (ImGui::Button("Difference")) showView(app, "albedo.difference");
  tooltip("Viewport: |database albedo - G-buffer albedo| (albedo.difference).");
  ImGui::SameLine();
  if (ImGui::Button("Impact")) {
    app.session().captureAlbedoBaseline();
    app.pinPreview("albedo.impact");
  }
  tooltip("Remembers the current image, then shows how much every later albedo edit changes it\n"
      "(albedo.impact): the colour bleeding the edit caused. Press again for a new baseline.");
}

void albedoPanel(EditorApp& app) {
  placeColumnPanel(ColumnPanel::Albedo);
  ImGui::Begin("Albedo");
  if (!app.session().hasScene()) {
    ImGui::TextDisabled("No scene.");
    ImGui::End();
    return;
  }
  auto& session = app.session();
  auto& lib = session.albedo();
  std::string& field = app.albedoDbField();
  static std::string fieldScene;  // a new scene proposes its own database
  if (fieldScene != session.scene().name) field.clear(), fieldScene = session.scene().name;
  if (field.empty())
    field = session.albedoDatabaseFile().value_or(app.defaultAlbedoDatabase()).string();
  char buf[512];
  std::snprintf(buf, sizeof buf, "%s", field.c_str());
  ImGui::SetNextItemWidth(-120);
  if (ImGui::InputText("##db", buf, sizeof buf)) field = buf;
  ImGui::SameLine();
  if (ImGui::Button("Open/Create")) {
    try {
      app.openAlbedoDatabase(field);
    } catch (const std::exception& e) {
      app.showError(e.what());
    }
  }
  tooltip("An SQLite albedo database: baked entries and artist overrides. Created when missing;\n"
      "a file that is not one is refused and left untouched.");
  if (const albedo::AlbedoDatabase* db = lib.database())
    ImGui::TextDisabled("%s: schema %d, revision %llu", db->file().filename().string().c_str(), db->schemaVersion(),
                        static_cast<unsigned long long>(db->revision()));
  else
    ImGui::TextDisabled("no database: rays read texture averages");

  if (const albedo::BakeJob* job = app.albedoBake()) {
    const auto& p = job->progress();
    ImGui::ProgressBar(p.total ? float(p.done) / float(p.total) : 1.0f, ImVec2(-90, 0),
                       fmt::format("{}/{} keys", p.done, p.total).c_str());
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) app.cancelAlbedoBake();
  } else {
    ImGui::BeginDisabled(!lib.database());
    if (ImGui::Button("Bake")) app.startAlbedoBake(false);
    trackItem("albedo.bake");
    tooltip("Render each mesh + material from 6 directions and store its visible average albedo.\n"
        "Keys already in the database are skipped.");
    ImGui::SameLine();
    if (ImGui::Button("Re-bake all")) app.startAlbedoBake(true);
    trackItem("albedo.rebake");
    ImGui::EndDisabled();
    if (!app.lastBakeSummary().empty()) ImGui::TextWrapped("%s", app.lastBakeSummary().c_str());
  }

  orphanSection(app);

  static int filter = 0;
  size_t counts[3] = {};
  for (const AlbedoEntry& e : lib.entries()) ++counts[int(e.source)];
  ImGui::TextDisabled("%zu keys: %zu override, %zu baked, %zu average", lib.entries().size(), counts[0], counts[1], counts[2]);
  ImGui::SetNextItemWidth(180);
  ImGui::Combo("Show", &filter, kFilterNames, IM_ARRAYSIZE(kFilterNames));

  // Long mesh / material labels scroll sideways rather than being cut off.
  const ImGuiTableFlags flags =
      ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY | ImGuiTableFlags_ScrollX | ImGuiTableFlags_BordersInnerV;
  if (ImGui::BeginTable("entries", 4, flags, ImVec2(0, -1))) {
    ImGui::TableSetupScrollFreeze(0, 1);
    ImGui::TableSetupColumn("", ImGuiTableColumnFlags_WidthFixed, 18.0f);
    ImGui::TableSetupColumn("mesh / material", ImGuiTableColumnFlags_WidthFixed);
    ImGui::TableSetupColumn("source", ImGuiTableColumnFlags_WidthFixed, 64.0f);
    ImGui::TableSetupColumn("flags", ImGuiTableColumnFlags_WidthFixed, 60.0f);
    ImGui::TableHeadersRow();
    const auto selected = app.selected();
    for (uint32_t c = 0; c < lib.entries().size(); ++c) {
      const AlbedoEntry& e = lib.entries()[c];
      if (!passes(e, Filter(filter))) continue;
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::ColorButton(fmt::format("##c{}", c).c_str(), colour(e.resolved), 0, ImVec2(14, 14));
      ImGui::TableNextColumn();
      const bool isSelected = selected && lib.combinationOf(*selected) == c;
      if (ImGui::Selectable(fmt::format("{}##row{}", e.combination.label, c).c_str(), isSelected,
                            ImGuiSelectableFlags_SpanAllColumns))
        app.select(e.combination.instances.empty() ? std::nullopt : std::optional<uint32_t>(e.combination.instances[0]));
      if (ImGui::IsItemHovered()) {
        std::string text = fmt::format("{}\nkey {}\n{} instance(s)\nresolved {:.3f} {:.3f} {:.3f}", e.combination.label,
                                       albedo::keyToHex(e.combination.key), e.combination.instances.size(), e.resolved.r,
                                       e.resolved.g, e.resolved.b);
        if (e.baked)
          text += fmt::format("\nbaked {}: coverage {:.2f}, view variance {:.4f}", e.baked->bakedAt, e.baked->coverage,
                              e.baked->viewVariance);
        ImGui::SetTooltip("%s", text.c_str());
      }
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(e.source == AlbedoSource::TextureAverage ? "average" : albedo::sourceName(e.source));
      ImGui::TableNextColumn();
      std::string flagText;
      if (e.stale) flagText += "stale ";
      else if (!e.baked) flagText += "missing ";
      if (e.baked && e.baked->viewVariance > kHighViewVariance) flagText += "view-dep.";
      ImGui::TextUnformatted(flagText.c_str());
    }
    ImGui::EndTable();
  }
  ImGui::End();
}

}  // namespace tl::editor
