// Never lose data: an output is written to a temporary file beside its final path and renamed into
// place only when complete. Until commit(), the destructor removes the temporary file.
#pragma once

#include <string>

namespace fcc::io {

// The checks every output of fccvdb gets before any work, one policy for all (convert, synth, render,
// view --screenshot): OutputError "PATH: exists; pass --force to overwrite it" unless `overwrite`,
// "PATH: cannot write there (directory 'D' does not exist)" or "(... is not writable)".
void checkOutputPath(const std::string& path, bool overwrite);

class AtomicOutput {
 public:
  // Refuses (OutputError) a final path equal to `input` (same file, also through links), then what
  // checkOutputPath refuses.
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

// A whole text (JSON, Markdown, SVG) written through an AtomicOutput; OutputError "cannot write PATH".
void writeTextFile(const std::string& path, const std::string& text, bool overwrite);

}  // namespace fcc::io
