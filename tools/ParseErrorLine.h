// The one line a command-line error prints: CLI11's message, "did you mean --X?" for a flag the
// subcommand does not have but has one close to, and where to look: the subcommand's own --help
// (fccvdb render --help), not the top level's.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace fcc::cli {

std::string parseErrorLine(CLI::App& app, const CLI::ParseError& error, int argc, const char* const* argv);

// The flag of `app` closest to `unknown` (edits, a swap of neighbours counting as one, at most a third
// of its length, at least 1), or "" if none is close.
std::string closestFlag(const CLI::App& app, const std::string& unknown);

}  // namespace fcc::cli
