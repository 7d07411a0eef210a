#pragma once
// Undo and redo of the window's edits (parameters, sources, sinks): each edit keeps the commands
// that redo and undo it. The history only keeps edits and hands back the commands to post; it
// knows no worker, so it is tested without a window (tests/app/test_edit_history.cpp).

#include <optional>
#include <string>
#include <vector>

#include "app/worker.h"

namespace scour {

struct Edit {
  std::vector<SimCommand> redo, undo;
  std::string what;  ///< shown in the log and the Undo/Redo tooltips
  std::string key;   ///< a parameter or source edit that a drag may extend ("" = never merged)
};

class EditHistory {
 public:
  /// Records an edit and returns the commands that perform it. With `extend`, an edit with the
  /// same key as the newest one merges into it (one slider or source drag, one undo step): the
  /// newest keeps its undo, from before the drag, and takes the new redo and `what`. Clears the redo
  /// stack.
  std::vector<SimCommand> perform(Edit e, bool extend);
  /// Takes back the newest edit and returns it (post its `undo`), or nothing if there is none.
  std::optional<Edit> undo();
  /// Does again the newest undone edit and returns it (post its `redo`), or nothing.
  std::optional<Edit> redo();
  /// A cancelled drag: if the newest edit has this key, takes it back for good (it cannot be
  /// redone) and returns it (post its `undo`).
  std::optional<Edit> cancel(const std::string& key);
  /// Forgets everything (a restored snapshot brings its own sources and sinks).
  void clear();

  const Edit* nextUndo() const { return undo_.empty() ? nullptr : &undo_.back(); }
  const Edit* nextRedo() const { return redo_.empty() ? nullptr : &redo_.back(); }

 private:
  std::vector<Edit> undo_, redo_;
};

}  // namespace scour
