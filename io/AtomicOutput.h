// Never lose data: an output is written to a temporary file beside its final path and renamed into
// place only when complete. Until commit(), the destructor removes the temporary file.
#pragma once

#include <string>

namespace fcc::io {

class AtomicOutput {
 public:
  // Refuses (OutputError) an existing `finalPath` unless `overwrite`, and a final path equal to any
  // of `inputs` (same file, also through links).
  AtomicOutput(std::string finalPath, bool overwrite, const std::string& input = {});
  ~AtomicOutput();
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;

  const std::string& tempPath() const { return tempPath_; }
  const std::string& finalPath() const { return finalPath_; }
  void commit();  // rename the temporary file onto the final path

 private:
  std::string finalPath_;
  std::string tempPath_;
  bool committed_ = false;
};

}  // namespace fcc::io
