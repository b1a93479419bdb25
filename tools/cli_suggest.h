#pragma once
// Unknown commands and options, said as such with the nearest known name, before CLI11 reports
// them in its own terms: `fscript run f.fs --backnd vm` passed "--backnd" and "vm" to the script
// as numbers ("'vm' is not a number"), and `fscript rn` said only that "rn" was not expected.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

namespace fscript::tools {

// Edits (insert, delete, replace, swap two neighbours) from a to b.
inline size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i)
    for (size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] != b[j - 1])});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

// The name of `names` nearest to `word`, if near enough to be a slip (a third of its letters, at
// least two), else "".
inline std::string nearest_name(const std::string& word, const std::vector<std::string>& names) {
  std::string best;
  size_t best_d = std::max<size_t>(2, word.size() / 3) + 1;
  for (const auto& n : names)
    if (size_t d = edit_distance(word, n); d < best_d) best = n, best_d = d;
  return best;
}

// "--long" and "-s" names of the options of `app` (and of the apps above it, which CLI11 also takes).
inline std::vector<std::string> option_names(const CLI::App* app) {
  std::vector<std::string> out;
  for (; app; app = app->get_parent())
    for (const CLI::Option* o : app->get_options()) {
      for (const auto& l : o->get_lnames()) out.push_back("--" + l);
      for (const auto& s : o->get_snames()) out.push_back("-" + s);
    }
  return out;
}

inline const CLI::Option* find_option(const CLI::App* app, const std::string& name) {
  for (; app; app = app->get_parent())
    if (const CLI::Option* o = app->get_option_no_throw(name)) return o;
  return nullptr;
}

// False, with the message in `error`, at the first unknown command or option of argv. The first
// word that is not an option must be a command of `app` when `words_are_commands` (fscript); an
// argument a command takes as a value ("-inf", "-1e3") is not an option.
inline bool check_command_line(const CLI::App& app, int argc, char** argv, bool words_are_commands, std::string& error) {
  const CLI::App* at = &app;
  std::string where = app.get_name().empty() ? std::string(argv[0]) : app.get_name();
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg == "--") return true;
    bool is_long = arg.rfind("--", 0) == 0, is_short = !is_long && arg.size() > 1 && arg[0] == '-';
    if (is_short || is_long) {
      std::string name = is_long ? arg.substr(0, arg.find('=')) : arg.substr(0, 2);
      if (is_short) {
        char* end = nullptr;
        std::strtod(arg.c_str(), &end);
        if (end && *end == '\0') continue;  // a number, or -inf, -nan
      }
      const CLI::Option* o = find_option(at, name);
      if (!o) {
        std::string near = nearest_name(name, option_names(at));
        error = "unknown option '" + name + "'" + (near.empty() ? "" : " (did you mean '" + near + "'?)");
        return false;
      }
      bool takes_value = o->get_type_size_max() > 0 && !(is_long && arg.find('=') != std::string::npos) &&
                         !(is_short && arg.size() > 2);
      if (takes_value) ++i;
      continue;
    }
    if (at == &app && words_are_commands) {
      const CLI::App* sub = nullptr;
      std::vector<std::string> commands;
      for (const CLI::App* s : app.get_subcommands([](const CLI::App*) { return true; })) {
        commands.push_back(s->get_name());
        if (s->get_name() == arg) sub = s;
      }
      if (!sub) {
        std::string near = nearest_name(arg, commands), list;
        for (const auto& c : commands) list += (list.empty() ? "" : ", ") + c;
        error = "unknown command '" + arg + "'" + (near.empty() ? "" : " (did you mean '" + near + "'?)") +
                "; the commands are " + list;
        return false;
      }
      at = sub;
    }
  }
  return true;
}

}  // namespace fscript::tools
