#include "ParseErrorLine.h"

#include <algorithm>
#include <cctype>
#include <vector>

namespace fcc::cli {
namespace {

// Edits between two words, a swap of neighbours counting as one (the commonest typo: --jsno).
size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i)
    for (size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

// A word that names a flag: "-x" or "--xyz", not "-" or a negative number ("-1,2,3" for --eye).
bool looksLikeFlag(const std::string& word) {
  return word.size() >= 2 && word[0] == '-' && !std::isdigit(static_cast<unsigned char>(word[1])) && word[1] != '.';
}

// The deepest subcommand the words name (fccvdb bench render ... -> "render" under "bench").
CLI::App* chosenSubcommand(CLI::App& app, int argc, const char* const* argv) {
  CLI::App* current = &app;
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (word.empty() || word[0] == '-') continue;
    const auto subs = current->get_subcommands([&](CLI::App* s) { return s->get_name() == word; });
    if (!subs.empty()) current = subs.front();
  }
  return current;
}

std::string commandPath(const CLI::App* app) {
  std::string path;
  for (const CLI::App* a = app; a; a = a->get_parent()) path = a->get_name() + (path.empty() ? "" : " " + path);
  return path;
}

}  // namespace

std::string closestFlag(const CLI::App& app, const std::string& unknown) {
  std::string best;
  size_t bestDistance = std::max<size_t>(1, unknown.size() / 3) + 1;
  for (const CLI::Option* option : app.get_options()) {
    std::vector<std::string> names;
    for (const std::string& l : option->get_lnames()) names.push_back("--" + l);
    for (const std::string& s : option->get_snames()) names.push_back("-" + s);
    for (const std::string& name : names) {
      const size_t d = editDistance(unknown, name);
      if (d < bestDistance) {
        bestDistance = d;
        best = name;
      }
    }
  }
  return best;
}

std::string parseErrorLine(CLI::App& app, const CLI::ParseError& error, int argc, const char* const* argv) {
  CLI::App* command = chosenSubcommand(app, argc, argv);
  std::string line = error.what();
  for (int i = 1; i < argc; ++i) {
    std::string word = argv[i];
    if (!looksLikeFlag(word)) continue;
    word = word.substr(0, word.find('='));
    if (command->get_option_no_throw(word) || app.get_option_no_throw(word)) continue;
    const std::string suggestion = closestFlag(*command, word);
    if (!suggestion.empty()) {
      line += "; " + word + ": did you mean " + suggestion + "?";
      break;
    }
  }
  return line + " (see " + commandPath(command) + " --help)";
}

}  // namespace fcc::cli
