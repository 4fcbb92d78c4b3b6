// One-line messages for CLI11 parse errors (parse_error_message.h).

#include "app/parse_error_message.h"

#include <cstdlib>
#include <regex>

#include <CLI/CLI.hpp>

#include "app/exit_codes.h"

namespace vegstream::app {
namespace {

// CLI::Range writes its bounds with std::to_string ("1.000000 to 1000.000000"): written back
// as the user would ("[1 - 1000]"), and a value that is no number at all is called that.
std::string tidyRange(const std::string& what) {
  static const std::regex range("Value (.*) not in range (\\S+) to (\\S+)$");
  std::smatch m;
  if (!std::regex_search(what, m, range)) return what;
  const auto trim = [](std::string n) {
    if (n.find('.') == std::string::npos) return n;
    while (n.back() == '0') n.pop_back();
    if (n.back() == '.') n.pop_back();
    return n;
  };
  const std::string value = m[1].str(), bounds = "[" + trim(m[2].str()) + " - " + trim(m[3].str()) + "]";
  char* end = nullptr;
  std::strtod(value.c_str(), &end);
  const bool number = !value.empty() && end != nullptr && *end == '\0';
  return m.prefix().str() + (number ? "Value " + value + " not in range " + bounds
                                    : "'" + value + "' is not a number (expected one in " + bounds + ")");
}

// "Could not convert: --threads = many" → "--threads: 'many' is not a valid INT" (the option's
// type as its --help shows it).
std::string tidyConversion(const CLI::App& app, const std::string& what) {
  static const std::regex conversion("^Could not convert: (\\S+) = (.*)$");
  std::smatch m;
  if (!std::regex_search(what, m, conversion)) return what;
  const CLI::Option* option = app.get_option_no_throw(m[1].str());
  const std::string type = option != nullptr ? option->get_type_name() : "";
  return m[1].str() + ": '" + m[2].str() + "' is not a valid " + (type.empty() ? std::string("value") : type);
}

std::string subcommandNames(const CLI::App& root) {
  std::string names;
  for (const CLI::App* sub : root.get_subcommands([](const CLI::App*) { return true; }))
    names += (names.empty() ? "" : ", ") + sub->get_name();
  return names;
}

}  // namespace

std::string parseErrorMessage(const CLI::App& root, const CLI::ParseError& error) {
  // Not root.get_name(): CLI11 sets it from argv[0], the executable's whole path.
  std::string where = "vegstream";
  // No subcommand was recognised: name what was given instead, and the subcommands there are.
  if (root.get_subcommands().empty()) {
    const std::vector<std::string> rest = root.remaining();
    if (!rest.empty())
      return where + ": unknown subcommand or option '" + rest.front() + "' (subcommands: " + subcommandNames(root) +
             ")";
    return where + ": a subcommand is required (" + subcommandNames(root) + ")";
  }
  // The innermost subcommand CLI11 had started on when it threw: it is pushed onto its parent's
  // parsed list before its own arguments are read.
  const CLI::App* app = &root;
  while (!app->get_subcommands().empty()) {
    app = app->get_subcommands().back();
    where += " " + app->get_name();
  }
  std::string what = tidyConversion(*app, tidyRange(oneLine(error.what())));
  if (what.empty()) what = error.get_name();
  return where + ": " + what;
}

}  // namespace vegstream::app
