#include "ParseErrorLine.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <limits>
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

// The deepest subcommand the words name (fccvdb bench render ... -> "render" under "bench"), and the
// index of the word after its name (1 for the application itself).
CLI::App* chosenSubcommand(CLI::App& app, int argc, const char* const* argv, int* after = nullptr) {
  CLI::App* current = &app;
  if (after) *after = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (word.empty() || word[0] == '-') continue;
    const auto subs = current->get_subcommands([&](CLI::App* s) { return s->get_name() == word; });
    if (!subs.empty()) {
      current = subs.front();
      if (after) *after = i + 1;
    }
  }
  return current;
}

std::string commandPath(const CLI::App* app) {
  std::string path;
  for (const CLI::App* a = app; a; a = a->get_parent()) path = a->get_name() + (path.empty() ? "" : " " + path);
  return path;
}

// The closest of `names` to `unknown` within a third of its length in edits, or else the one name
// that starts `unknown` or that `unknown` starts (--isovalue for --iso, --lay for --layout); "" if none.
std::string closestName(const std::vector<std::string>& names, const std::string& unknown) {
  std::string best;
  size_t bestDistance = std::max<size_t>(1, unknown.size() / 3) + 1;
  for (const std::string& name : names) {
    const size_t d = editDistance(unknown, name);
    if (d < bestDistance) {
      bestDistance = d;
      best = name;
    }
  }
  if (!best.empty()) return best;
  std::vector<std::string> prefixed;
  for (const std::string& name : names)
    if (name.size() >= 3 && unknown.size() >= 3 && (unknown.rfind(name, 0) == 0 || name.rfind(unknown, 0) == 0))
      prefixed.push_back(name);
  return prefixed.size() == 1 ? prefixed.front() : "";
}

// The type CLI11 gives option `name` of `command` (FLOAT, INT:POSITIVE, ...); "" for no such option.
std::string typeNameOf(const CLI::App& command, const std::string& name) {
  const CLI::Option* option = command.get_option_no_throw(name);
  return option ? option->get_type_name() : "";
}

// CLI11's "Could not convert: --iso = abc" as "--iso 'abc': expected a number".
std::string conversionMessage(const CLI::App& command, const std::string& what) {
  const std::string head = "Could not convert: ";
  const std::size_t equals = what.find(" = ");
  if (what.rfind(head, 0) != 0 || equals == std::string::npos) return what;
  const std::string name = what.substr(head.size(), equals - head.size()), value = what.substr(equals + 3);
  const std::string type = typeNameOf(command, name);
  const std::string expected = type.empty()      ? "another value"
                               : type == "FLOAT" ? "a number"
                               : type == "INT"   ? "a whole number"
                               : type == "UINT"  ? "a whole number, 0 or more"
                                                 : "a value of type " + type;
  return name + " '" + value + "': expected " + expected;
}

// CLI::Range's "--frames: Value 0 not in range 0.000000 to 1797...(309 digits).000000" with the bounds
// as a person says them (PositiveNumber's lower bound is DBL_MIN, printed as 0: the option's type,
// INT:POSITIVE or FLOAT:NONNEGATIVE, tells them apart, and whether the number is whole).
std::string rangeMessage(const CLI::App& command, const std::string& what) {
  const std::size_t valueAt = what.find(": Value "), rangeAt = what.find(" not in range ");
  const std::size_t toAt = rangeAt == std::string::npos ? std::string::npos : what.find(" to ", rangeAt);
  if (valueAt == std::string::npos || toAt == std::string::npos || valueAt > rangeAt) return what;
  const std::string name = what.substr(0, valueAt), value = what.substr(valueAt + 8, rangeAt - valueAt - 8);
  const double lo = std::strtod(what.c_str() + rangeAt + 14, nullptr), hi = std::strtod(what.c_str() + toAt + 4, nullptr);
  const auto number = [](double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return std::string(text);
  };
  const std::string type = typeNameOf(command, name);
  const bool positive = type.find("POSITIVE") != std::string::npos && type.find("NONNEGATIVE") == std::string::npos;
  const bool whole = type.rfind("INT", 0) == 0 || type.rfind("UINT", 0) == 0;
  const bool unbounded = hi >= 0.5 * std::numeric_limits<double>::max();
  const std::string valid = !unbounded  ? "from " + number(lo) + " to " + number(hi)
                            : positive  ? "above 0"
                            : lo == 0.0 ? "0 or more"
                                        : "at least " + number(lo);
  return name + " '" + value + "': expected " + (whole ? "a whole number " : "a number ") + valid;
}

// "The following arguments were not expected: c b a" in the order given (CLI11 2.1 lists them reversed).
std::string extrasMessage(const std::string& what) {
  const std::size_t colon = what.find(": ");
  if (colon == std::string::npos) return what;
  std::vector<std::string> words;
  for (std::size_t at = colon + 2; at < what.size();) {
    const std::size_t end = std::min(what.find(' ', at), what.size());
    words.push_back(what.substr(at, end - at));
    at = end + 1;
  }
  std::string inOrder;
  for (auto w = words.rbegin(); w != words.rend(); ++w) inOrder += (inOrder.empty() ? "" : " ") + *w;
  return what.substr(0, colon + 2) + inOrder;
}

// CLI11's own words, made plainer where they are a program's rather than a person's.
std::string plainerMessage(const CLI::App& command, const CLI::ParseError& error) {
  const std::string what = error.what();
  if (dynamic_cast<const CLI::ConversionError*>(&error)) return conversionMessage(command, what);
  if (dynamic_cast<const CLI::ValidationError*>(&error)) return rangeMessage(command, what);
  if (dynamic_cast<const CLI::ExtrasError*>(&error)) return extrasMessage(what);
  return what;
}

}  // namespace

std::string closestFlag(const CLI::App& app, const std::string& unknown) {
  // A short flag is one letter: any other letter is one edit away, so no guess (-r is not -h).
  if (unknown.size() <= 2) return "";
  std::vector<std::string> names;
  for (const CLI::Option* option : app.get_options())
    for (const std::string& l : option->get_lnames())
      if (l != "help") names.push_back("--" + l);
  return closestName(names, unknown);
}

std::string parseErrorLine(CLI::App& app, const CLI::ParseError& error, int argc, const char* const* argv) {
  int after = 1;
  CLI::App* command = chosenSubcommand(app, argc, argv, &after);
  const std::vector<CLI::App*> subcommands = command->get_subcommands([](CLI::App*) { return true; });
  // A command of commands (fccvdb, fccvdb bench) given a word that names none of them.
  for (int i = after; i < argc && !subcommands.empty(); ++i) {
    const std::string word = argv[i];
    if (word.empty() || word[0] == '-') continue;
    std::vector<std::string> names;
    std::string valid;
    for (const CLI::App* s : subcommands) {
      names.push_back(s->get_name());
      valid += (valid.empty() ? "" : ", ") + s->get_name();
    }
    const std::string suggestion = closestName(names, word);
    return "unknown command '" + word + "'" + (suggestion.empty() ? "" : ": did you mean " + suggestion + "?") +
           " (valid: " + valid + "; see " + commandPath(command) + " --help)";
  }
  std::string line = plainerMessage(*command, error);
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
