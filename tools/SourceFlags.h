// Flags that say how to read a Cartesian input (raw layout), shared by `convert`, `render`, `view` and
// `bench render`, which all take any input `convert` takes.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <optional>
#include <string>

#include "io/DenseVolume.h"

namespace fcc::cli {

struct SourceFlags {
  std::string dims, type = "u8", endian = "little", spacing = "1,1,1";
  uint64_t headerBytes = 0;
  CLI::Option* dimsOption = nullptr;
  CLI::Option* typeOption = nullptr;
  CLI::Option* endianOption = nullptr;
  CLI::Option* spacingOption = nullptr;
  CLI::Option* headerBytesOption = nullptr;
};

// Registers --dims, --type, --endian, --spacing, --header-bytes.
void addRawFlags(CLI::App& app, SourceFlags& flags);

// The raw layout the flags give (nullopt without --dims). A raw-only flag given for an input that is
// not raw (by its extension) is a ValueError: it would be silently ignored.
std::optional<io::RawLayout> rawLayoutFromFlags(const SourceFlags& flags, const std::string& input);

}  // namespace fcc::cli
