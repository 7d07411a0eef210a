// Undo and redo without a window: the history hands back the commands to post, in order.
#include <catch2/catch.hpp>

#include "app/edit_history.h"

using namespace scour;

namespace {

Edit setParam(const std::string& key, const std::string& from, const std::string& to) {
  return {{cmd::SetParam{key, to}}, {cmd::SetParam{key, from}}, key + " = " + to, key};
}

// The value a list of commands sets, for one SetParam.
std::string value(const std::vector<SimCommand>& commands) {
  REQUIRE(commands.size() == 1);
  return std::get<cmd::SetParam>(commands[0]).value;
}

}  // namespace

TEST_CASE("undo and redo walk the edits back and forth", "[app][history]") {
  EditHistory h;
  CHECK_FALSE(h.undo());
  CHECK_FALSE(h.redo());
  CHECK(value(h.perform(setParam("erosion.k_eps", "0.1", "0.5"), false)) == "0.5");
  CHECK(value(h.perform(setParam("erosion.tau_c", "3", "5"), false)) == "5");
  REQUIRE(h.nextUndo() != nullptr);
  CHECK(h.nextUndo()->what == "erosion.tau_c = 5");

  std::optional<Edit> e = h.undo();
  REQUIRE(e);
  CHECK(value(e->undo) == "3");
  CHECK(value(h.undo()->undo) == "0.1");
  CHECK_FALSE(h.undo());  // nothing left
  CHECK(value(h.redo()->redo) == "0.5");
  CHECK(h.nextRedo()->what == "erosion.tau_c = 5");

  // A new edit drops what could be redone.
  h.perform(setParam("sediment.diffusion", "0.01", "0.02"), false);
  CHECK(h.nextRedo() == nullptr);
  CHECK(value(h.undo()->undo) == "0.01");
  CHECK(value(h.undo()->undo) == "0.1");
}

TEST_CASE("a drag is one edit: it keeps the value from before it", "[app][history]") {
  EditHistory h;
  h.perform(setParam("erosion.k_eps", "0.1", "0.2"), true);
  h.perform(setParam("erosion.k_eps", "0.2", "0.3"), true);
  CHECK(value(h.perform(setParam("erosion.k_eps", "0.3", "0.4"), true)) == "0.4");
  h.perform(setParam("erosion.tau_c", "3", "4"), true);  // another key: a new edit
  CHECK(value(h.undo()->undo) == "3");
  std::optional<Edit> drag = h.undo();
  CHECK(value(drag->undo) == "0.1");
  CHECK(value(drag->redo) == "0.4");
  CHECK_FALSE(h.undo());
  // Without `extend` the same key is a new edit; an empty key never merges.
  h.perform(setParam("erosion.k_eps", "0.1", "0.2"), false);
  h.perform(setParam("erosion.k_eps", "0.2", "0.3"), false);
  CHECK(value(h.undo()->undo) == "0.2");
  Edit a{{cmd::RemoveSource{0}}, {cmd::RemoveSource{1}}, "a", ""}, b = a;
  h.perform(a, true);
  h.perform(b, true);
  CHECK(h.undo());
  CHECK(h.undo());
}

TEST_CASE("a cancelled drag is taken back and cannot be redone", "[app][history]") {
  EditHistory h;
  h.perform(setParam("erosion.k_eps", "0.1", "0.2"), false);
  h.undo();  // something to redo before the drag
  h.perform(setParam("erosion.tau_c", "3", "4"), false);
  CHECK_FALSE(h.cancel("move source 0"));  // the newest edit is not that drag
  Edit move{{cmd::RemoveSource{7}}, {cmd::RemoveSource{8}}, "move source 0", "move source 0"};
  h.perform(move, true);
  std::optional<Edit> e = h.cancel("move source 0");
  REQUIRE(e);
  CHECK(std::get<cmd::RemoveSource>(e->undo[0]).index == 8);
  CHECK(h.nextRedo() == nullptr);
  CHECK(value(h.undo()->undo) == "3");
  h.clear();
  CHECK_FALSE(h.undo());
  CHECK_FALSE(h.redo());
}
