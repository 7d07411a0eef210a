#include "app/edit_history.h"

namespace scour {

std::vector<SimCommand> EditHistory::perform(Edit e, bool extend) {
  std::vector<SimCommand> commands = e.redo;
  if (extend && !undo_.empty() && !e.key.empty() && undo_.back().key == e.key) {
    undo_.back().redo = std::move(e.redo);
    undo_.back().what = std::move(e.what);
  }
  else
    undo_.push_back(std::move(e));
  redo_.clear();
  return commands;
}

std::optional<Edit> EditHistory::undo() {
  if (undo_.empty()) return std::nullopt;
  redo_.push_back(std::move(undo_.back()));
  undo_.pop_back();
  return redo_.back();
}

std::optional<Edit> EditHistory::redo() {
  if (redo_.empty()) return std::nullopt;
  undo_.push_back(std::move(redo_.back()));
  redo_.pop_back();
  return undo_.back();
}

std::optional<Edit> EditHistory::cancel(const std::string& key) {
  if (undo_.empty() || undo_.back().key != key) return std::nullopt;
  Edit e = std::move(undo_.back());
  undo_.pop_back();
  return e;
}

void EditHistory::clear() {
  undo_.clear();
  redo_.clear();
}

}  // namespace scour
