// Undo and redo of the editor's render-settings and lighting edits. The history watches
// the state rather than the widgets: each observed change becomes one step that names the
// schema entries it changed (render_settings.h: a new setting is undoable with no new code)
// and the lighting, whatever made it (a panel widget, Paste JSON, Defaults, a preset, a
// script's `set`). Undo writes back only what the step changed, entry by entry, so the image
// size the viewport sets and other entries edited since are left alone.
#pragma once

#include "lighting/common/render_settings.h"
#include "session/session.h"

#include <optional>
#include <string>
#include <vector>

namespace tl::session {

class EditHistory {
 public:
  // Forgets every step; `settings` and `lighting` are the state to watch from (a scene as it
  // opened: its own lighting, the lighting file applied, the default sun given).
  void reset(const lighting::RenderSettings& settings, const Lighting& lighting);
  // Compares the state with the last one observed and records the difference as a step.
  // `continuing` (a drag still under way) folds it into the previous step when that step
  // changed the same things. Returns whether anything changed. Before the first reset() there
  // is no state to compare with: the first observation only becomes it (a history never
  // holds the scene's loading as an edit, which an undo would take back).
  bool observe(const lighting::RenderSettings& settings, const Lighting& lighting, bool continuing);
  bool canUndo() const { return done_ > 0; }
  bool canRedo() const { return done_ < steps_.size(); }
  // Applies the step's before (undo) or after (redo) values to `settings` and `lighting`.
  bool undo(lighting::RenderSettings& settings, Lighting& lighting);
  bool redo(lighting::RenderSettings& settings, Lighting& lighting);
  // What the next undo or redo changes, for people: "shadowMapSize 2048 -> 512", "lighting".
  std::string undoLabel() const;
  std::string redoLabel() const;
  size_t steps() const { return steps_.size(); }
  // When the step an undo or a redo would act on was made (steady-clock seconds; see
  // AlbedoLibrary::undoTime).
  std::optional<double> undoTime() const;
  std::optional<double> redoTime() const;

 private:
  struct Change {
    const lighting::SettingInfo* setting;
    double before, after;
  };
  struct Step {
    std::vector<Change> settings;
    std::optional<Lighting> lightingBefore, lightingAfter;  // both or neither
    double madeAt = 0.0;
    bool sameKind(const Step& other) const;
  };
  static std::string describe(const Step& step, bool forward);
  void apply(const Step& step, bool forward, lighting::RenderSettings& settings, Lighting& lighting);
  std::vector<Step> steps_;
  size_t done_ = 0;  // steps_[0, done_) are applied
  bool watching_ = false;  // a state to compare with was given (reset) or taken (the first observe)
  lighting::RenderSettings seenSettings_;
  Lighting seenLighting_;
};

bool sameLighting(const Lighting& a, const Lighting& b);
// Whether two lights are the same to an artist: everything that shapes the light its kind
// casts (a point light's direction or a spot's width, which nothing reads, left out), vectors
// within float rounding (a light read back from a glTF went through its node's rotation). The
// node it is saved to is bookkeeping, not an edit. So a light deleted and added again where a
// saved one stood is no unsaved work, whether the saved one was made in this session or read.
bool sameLight(const scene::Light& a, const scene::Light& b);

}  // namespace tl::session
