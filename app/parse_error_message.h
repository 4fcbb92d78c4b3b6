#pragma once
// One line for a command-line parse error caught by CLI11 (app/README.md: a user mistake is one
// message naming the option and the problem, exit 2). CLI11's own `App::exit` prints the error
// and then "Run with --help for more information." — two lines; this names the subcommand being
// parsed instead: "vegstream record: --fps: Value 0 not in range [1 - 1000]".

#include <string>

namespace CLI {
class App;
class ParseError;
}  // namespace CLI

namespace vegstream::app {

// `root` is the top-level app after its parse threw `error`. The result has no line break.
std::string parseErrorMessage(const CLI::App& root, const CLI::ParseError& error);

}  // namespace vegstream::app
