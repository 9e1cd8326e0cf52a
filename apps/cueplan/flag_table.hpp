// Flags declared as data: a command lists its flags in a table - the name, the member of
// its arguments struct the value goes to, the type shown in --help, the help text and
// whether --help shows the default - and register_flags adds them to a CLI11 command in
// the table's order. A bool member is a switch (a flag without a value).
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

namespace cueplan::cli {

template <class Args>
struct Flag {
  using Member = std::variant<std::string Args::*, int Args::*, double Args::*, std::uint64_t Args::*,
                              bool Args::*>;
  const char* name;
  Member member;
  const char* type_name;  // the value's name in --help; unused for a switch
  std::string help;
  bool show_default = true;
};

template <class Args>
void register_flags(CLI::App& command, Args* args, const std::vector<Flag<Args>>& flags,
                    const char* group) {
  for (const Flag<Args>& flag : flags)
    std::visit(
        [&](auto member) {
          auto& value = args->*member;
          if constexpr (std::is_same_v<std::remove_reference_t<decltype(value)>, bool>) {
            command.add_flag(flag.name, value, flag.help)->group(group);
          } else {
            CLI::Option* option = command.add_option(flag.name, value, flag.help)->type_name(flag.type_name);
            if (flag.show_default) option->capture_default_str();
            option->group(group);
          }
        },
        flag.member);
}

}  // namespace cueplan::cli
