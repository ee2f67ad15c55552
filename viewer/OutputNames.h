// Names for what the viewer writes on a key (screenshots, cameras): timestamped, never an existing file.
#pragma once

#include <string>
#include <vector>

namespace fcc::render {

// "DIR/PREFIX-20261121-153012" (local time), with "-2", "-3", ... appended while DIR holds a file of
// that stem with any of `extensions` (".png", ...). `directory` empty: the current directory.
std::string uniqueTimestampedStem(const std::string& directory, const std::string& prefix,
                                  const std::vector<std::string>& extensions);

}  // namespace fcc::render
