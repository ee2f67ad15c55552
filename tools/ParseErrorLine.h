// The one line a command-line error prints: CLI11's message (a bad value, a range or words not
// expected said in plain words: "--frames '0': expected a whole number above 0"), "did you mean --X?" for a flag the
// subcommand does not have but has one close to, and where to look: the subcommand's own --help
// (fccvdb render --help), not the top level's. A word that names no subcommand where one is needed
// (fccvdb rendr) is "unknown command", with the closest and the valid ones.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace fcc::cli {

std::string parseErrorLine(CLI::App& app, const CLI::ParseError& error, int argc, const char* const* argv);

// The long flag of `app` closest to `unknown` (edits, a swap of neighbours counting as one, at most a
// third of its length, at least 1; else the one flag that starts it or that it starts: --isovalue is
// --iso), or "" if none is close. --help and one-letter flags are never guessed (any letter is one
// edit from -h).
std::string closestFlag(const CLI::App& app, const std::string& unknown);

}  // namespace fcc::cli
