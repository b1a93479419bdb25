#pragma once
// Unknown commands and options, said as such with the nearest known name, before CLI11 reports
// them in its own terms: `fscript run f.fs --backnd vm` passed "--backnd" and "vm" to the script
// as numbers ("'vm' is not a number"), and `fscript rn` said only that "rn" was not expected.
#include <CLI/CLI.hpp>
#include <cstdlib>
#include <string>
#include <vector>

#include "runtime/support/suggest.h"

namespace fscript::tools {

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
inline bool check_command_line(const CLI::App& app, int argc, char** argv, bool words_are_commands,
                               std::string& error) {
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
        std::string near = support::nearest_name(name, option_names(at));
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
        std::string near = support::nearest_name(arg, commands), list;
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
