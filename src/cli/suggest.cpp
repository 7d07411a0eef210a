// "Did you mean" for the command line, as the scene reader has for keys: a misspelled option
// gets the nearest one its command has, a misspelled command the nearest command.
#include <algorithm>
#include <string>

#include "cli/commands.h"
#include "engine/params.h"

namespace scour {

namespace {

std::vector<std::string> optionNames(const CLI::App& cmd) {
  std::vector<std::string> names = {"--help"};
  for (const CLI::Option* o : cmd.get_options()) {
    for (const std::string& l : o->get_lnames()) names.push_back("--" + l);
    for (const std::string& s : o->get_snames()) names.push_back("-" + s);
  }
  return names;
}

}  // namespace

std::string commandLineHint(const CLI::App& app, int argc, char** argv) {
  // The command in use: the first word that names one (the window's options otherwise).
  const CLI::App* cmd = &app;
  std::string name = "scour";
  for (int i = 1; i < argc && cmd == &app; ++i)
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
      if (argv[i] == sub->get_name()) cmd = sub, name = "scour " + sub->get_name();
  const std::vector<std::string> known = optionNames(*cmd);
  for (int i = 1; i < argc; ++i) {
    std::string word = argv[i];
    if (word.size() < 2 || word[0] != '-' || word == "--") continue;
    word = word.substr(0, word.find('='));
    if (std::find(known.begin(), known.end(), word) != known.end()) continue;
    if (word[1] != '-' && word.size() == 2) continue;  // a short flag or a negative number
    const std::string near = nearestName(word, known, slipDistance(word));
    return "unknown option '" + word + "' for '" + name + "'" +
           (near.empty() ? " ('" + name + " --help' lists them)"
                         : "; did you mean '" + near + "'?");
  }
  return "";
}

std::string commandHint(const CLI::App& app, const std::string& word) {
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    names.push_back(sub->get_name());
  const std::string near = nearestName(word, names, slipDistance(word));
  return near.empty() ? "" : "did you mean the command 'scour " + near + "'?";
}

}  // namespace scour
