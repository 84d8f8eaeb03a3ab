// The autosave's debounce. See autosave_timer.h.
#include "autosave_timer.h"

namespace aq::editor {

bool AutosaveTimer::due(double now, uint64_t revision, bool in_gesture) {
  if (!started_) {  // the document as opened: nothing to save yet
    started_ = true;
    seen_revision_ = written_revision_ = revision;
    changed_at_ = written_at_ = now;
    return false;
  }
  if (revision != seen_revision_) {
    seen_revision_ = revision;
    changed_at_ = now;
  }
  if (revision == written_revision_) return false;
  if (!in_gesture && now - changed_at_ >= debounce_) return true;
  return now - written_at_ >= period_;  // a drag that goes on for long is saved too
}

void AutosaveTimer::written(double now, uint64_t revision) {
  written_revision_ = revision;
  written_at_ = now;
}

}  // namespace aq::editor
