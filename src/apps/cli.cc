#include "apps/cli.h"

#include <CLI/CLI.hpp>
#include <algorithm>

#include "apps/commands.h"
#include "core/errors.h"
#include "io/provenance.h"

namespace beamid::apps {
namespace {

// An error as the line the user reads: "beamid <command>: " before it (the store's, merge's and report's errors
// began with a bare "beamid:": the sixth pass's S366-S475), or "beamid: " outside a command, unless it already
// begins with "beamid <command>:" (it read "beamid: beamid fit: ..." before).
std::string prefixed(const std::string& what, const std::string& command = "") {
  if (what.rfind("beamid ", 0) == 0) return what;
  return (command.empty() ? "beamid: " : "beamid " + command + ": ") + what;
}

std::string command_list() {
  std::string s;
  for (const Command& c : commands()) s += (s.empty() ? "" : ", ") + c.name;
  return s;
}

// The words CLI11 lists after "...not expected: " (it joins them in reverse order).
std::vector<std::string> extras_of(const std::string& message) {
  std::vector<std::string> words;
  const auto colon = message.find(": ");
  std::string rest = colon == std::string::npos ? message : message.substr(colon + 2);
  std::size_t start = 0;
  while (start < rest.size()) {
    const auto space = rest.find(' ', start);
    words.push_back(rest.substr(start, space == std::string::npos ? std::string::npos : space - start));
    if (space == std::string::npos) break;
    start = space + 1;
  }
  return {words.rbegin(), words.rend()};
}

// CLI11's error as the project's one-line message (without the "beamid: " prefix).
std::string message_of(const CLI::ParseError& e, const std::string& command, bool has_separator) {
  const std::string what = e.what();
  const std::string where = command.empty() ? "" : command + ": ";
  const auto name_end = what.find(": ");
  const std::string name = name_end == std::string::npos ? "" : what.substr(0, name_end);
  if (dynamic_cast<const CLI::ValidationError*>(&e) && name_end != std::string::npos)
    return where + name + " = " + what.substr(name_end + 2);  // "--dt = 'fast': must be a finite number"
  if (dynamic_cast<const CLI::ArgumentMismatch*>(&e) && name_end != std::string::npos)
    return where + name + (what.find("received") != std::string::npos ? " given twice" : " needs a value");
  if (dynamic_cast<const CLI::ExtrasError*>(&e)) {
    const std::vector<std::string> extras = extras_of(what);
    if (command.empty())
      return "unknown command '" + (extras.empty() ? std::string() : extras.front()) +
             "' (commands: " + command_list() + ")";
    for (const auto& x : extras)
      if (x.rfind("-", 0) == 0)
        return where + (has_separator
                            ? "'" + x +
                                  "' follows '--', which ends the flags, so it is read as an argument, not a flag: "
                                  "drop the '--'"
                            : "unknown flag " + x + " (" + command + " --help lists them)");
    return where + "unexpected argument '" + (extras.empty() ? std::string() : extras.front()) + "'";
  }
  return where + what;
}

}  // namespace

namespace {

const Command& find_command(const std::string& name) {
  for (const Command& c : commands())
    if (c.name == name) return c;
  throw InputError("unknown command '" + name + "' (commands: " + command_list() + ")");
}

// The command as a subcommand of `app`, with its flags and exclusions.
CLI::App* add_command(CLI::App& app, const Command& command) {
  CLI::App* sub = app.add_subcommand(command.name, command.summary);
  add_flags(*sub, command.flags);
  for (const auto& [a, b] : command.excludes) sub->get_option("--" + a)->excludes(sub->get_option("--" + b));
  return sub;
}

// Parses and, when `run`, runs the command: the one body of run_command_line and check_command_line.
int dispatch(const std::vector<std::string>& args, std::ostream& out, std::ostream& err, bool run) {
  if (args.size() <= 1) {
    out << overview();
    return 2;
  }
  CLI::App app{overview(), "beamid"};
  app.set_help_flag("-h,--help", "print the commands (or, after a command, its flags)");
  bool version = false;
  app.add_flag("--version", version, "print the version and the commit");
  app.require_subcommand(0, 1);
  std::vector<std::pair<const Command*, CLI::App*>> subcommands;
  for (const Command& c : commands()) {
    subcommands.emplace_back(&c, add_command(app, c));
  }
  const auto active = [&]() -> std::pair<const Command*, CLI::App*> {
    for (const auto& [c, sub] : subcommands)
      if (sub->parsed()) return {c, sub};
    return {nullptr, nullptr};
  };
  // A flag before the command belongs to no command: "beamid --beam b.toml simulate" was told "--beam is required".
  if (args.size() > 2 && args[1].rfind("-", 0) == 0 && args[1] != "-h" && args[1] != "--help" && args[1] != "--version")
    for (std::size_t k = 2; k < args.size(); ++k)
      for (const Command& c : commands())
        if (args[k] == c.name) {
          err << "beamid: "
              << one_line("'" + args[1] + "' comes before the command '" + c.name +
                          "': flags follow the command (beamid " + c.name + " " + args[1] + " ...)")
              << "\n";
          return 2;
        }
  std::vector<std::string> reversed(args.rbegin(), args.rend() - 1);  // CLI11 takes the arguments reversed
  try {
    app.parse(reversed);
  } catch (const CLI::CallForHelp&) {
    const auto [c, sub] = active();
    // "beamid fitt --help": the help flag is seen before the unknown word; the word, not the help, is the answer.
    if (!sub && args[1].rfind("-", 0) != 0) {
      err << "beamid: " << one_line("unknown command '" + args[1] + "' (commands: " + command_list() + ")") << "\n";
      return 2;
    }
    out << (sub ? sub->help("beamid") : overview());
    return 0;
  } catch (const CLI::ParseError& e) {
    const auto [c, sub] = active();
    const bool separator = std::find(args.begin(), args.end(), "--") != args.end();
    err << prefixed(one_line(message_of(e, c ? "beamid " + c->name : "", separator))) << "\n";
    return 2;
  }
  if (version) {
    out << "beamid " << io::version() << " (commit " << io::commit_label() << ")\n";
    return 0;
  }
  const auto [command, sub] = active();
  if (command == nullptr) {
    out << overview();
    return 2;
  }
  try {
    const std::vector<std::string> rest(args.begin() + 2, args.end());
    const Flags flags(command->name, *sub, command->flags, rest);
    return run ? command->run(flags, out) : 0;
  } catch (const InputError& error) {
    err << prefixed(error.what(), command->name) << "\n";
    return 2;
  } catch (const NumericalError& error) {
    err << prefixed(error.what(), command->name) << "\n";
    return 3;
  } catch (const OutputError& error) {
    err << prefixed(error.what(), command->name) << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    // Every input that sizes the work is guarded before it runs; a request that still exceeds the memory the process
    // may have (a ulimit, a cgroup) says so instead of "internal error: std::bad_alloc".
    err << prefixed(
               "out of memory: this run needs more memory than the process may use here (a ulimit or a "
               "container's limit); give smaller inputs, or run where more memory is available",
               command->name)
        << "\n";
    return 1;
  } catch (const std::exception& error) {
    err << "beamid: internal error: " << error.what() << "\n";
    return 1;
  }
}

}  // namespace

int run_command_line(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  return dispatch(args, out, err, true);
}

int check_command_line(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  return dispatch(args, out, err, false);
}

std::string command_help(const std::string& name) {
  const Command& command = find_command(name);
  CLI::App app{command.summary, "beamid"};
  return add_command(app, command)->help("beamid");
}

Flags parse_flags(const std::string& name, const std::vector<std::string>& arguments) {
  const Command* command = &find_command(name);
  CLI::App app{command->summary, "beamid"};
  CLI::App* sub = add_command(app, *command);
  std::vector<std::string> reversed(arguments.rbegin(), arguments.rend());  // CLI11 takes the arguments reversed
  reversed.push_back(command->name);
  try {
    app.parse(reversed);
  } catch (const CLI::CallForHelp&) {
    throw InputError("beamid " + name + ": --help: the flags are listed by `beamid " + name + " --help`");
  } catch (const CLI::ParseError& e) {
    throw InputError(
        message_of(e, "beamid " + name, std::find(arguments.begin(), arguments.end(), "--") != arguments.end()));
  }
  return Flags(command->name, *sub, command->flags, arguments);
}

}  // namespace beamid::apps
