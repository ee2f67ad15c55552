// The viewer's loop over files (`fccvdb view`): a session runs until it asks for another file (dropped
// on the window, or typed after O; ViewerSession::takeOpenRequest), which replaces it in the same
// window. Window-system free, so the tests drive it through the headless session harness with the
// same code `fccvdb view` runs (tests/viewer/test_viewer_session.cpp).
#pragma once

#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "ViewerSession.h"

namespace fcc::render {

// Runs `session` with `run(session&)` (the window's frame loop: nullopt when the window closes, else
// the path asked for) until the window closes. A path asked for is opened with `open(path)` (a
// Dataset, or an exception whose what() is one line); when that fails the old session and dataset
// stay and the session says why over the image ("cannot open it: ..."). Else the old session is
// destroyed, then the old dataset (`data` is assigned: the session reads it, so never the other way
// round), and `makeSession(data)` builds the new one; `opened(path)` is called after.
template <class Dataset, class Run, class Open, class MakeSession, class Opened>
void runOpeningFiles(Dataset& data, std::unique_ptr<ViewerSession>& session, Run&& run, Open&& open,
                     MakeSession&& makeSession, Opened&& opened) {
  while (std::optional<std::string> next = run(*session)) {
    std::optional<Dataset> candidate;
    try {
      candidate.emplace(open(*next));  // a Cartesian file is converted first: the window waits
    } catch (const std::exception& e) {  // fcc::Error's one line, or anything a reader threw
      session->notify(std::string("cannot open it: ") + e.what());
      continue;
    }
    session.reset();  // before the data it reads
    data = std::move(*candidate);
    session = makeSession(data);
    opened(*next);
  }
}

}  // namespace fcc::render
