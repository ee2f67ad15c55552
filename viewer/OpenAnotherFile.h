// The viewer's loop over files (`fccvdb view`): a session runs until it asks for another file (dropped
// on the window, or typed after O) or for its own data with another reconstruction (the panel's combo;
// ViewerSession::takeOpenRequest), which replaces it in the same window. Window-system free, so the
// tests drive it through the headless session harness with the same code `fccvdb view` runs
// (tests/viewer/test_viewer_session.cpp).
#pragma once

#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "ViewerSession.h"

namespace fcc::render {

// Runs `session` with `run(session&)` (the window's frame loop: nullopt when the window closes, else
// the OpenRequest asked for) until the window closes. Another file is opened with `open(path)`, the same
// data with another reconstruction with `reopen(reconstruction)` (each a Dataset, or an exception whose
// what() is one line); when that fails the old session and dataset stay and the session says why over
// the image ("cannot open it: ...", "cannot switch to NAME: ..."). Else the old session is destroyed,
// then the old dataset (`data` is assigned: the session reads it, so never the other way round), and
// `makeSession(data)` builds the new one, which for the same data takes on the old one's view (camera,
// settings, transfer function: ViewerSession::restoreView) and for another file the transfer-function
// editor's undo history (ViewerSession::continueTransferHistory: its own function, and ctrl + Z brings
// back the last file's); `opened(request)` is called after.
template <class Dataset, class Run, class Open, class Reopen, class MakeSession, class Opened>
void runOpeningFiles(Dataset& data, std::unique_ptr<ViewerSession>& session, Run&& run, Open&& open, Reopen&& reopen,
                     MakeSession&& makeSession, Opened&& opened) {
  while (std::optional<OpenRequest> next = run(*session)) {
    const bool sameData = next->path.empty();
    std::optional<Dataset> candidate;
    try {
      // A Cartesian file is converted first: the window waits.
      if (sameData) candidate.emplace(reopen(next->reconstruction));
      else candidate.emplace(open(next->path));
    } catch (const std::exception& e) {  // fcc::Error's one line, or anything a reader threw
      session->notify((sameData ? "cannot switch to " + next->reconstruction + ": " : std::string("cannot open it: ")) + e.what());
      continue;
    }
    std::optional<SessionView> kept;
    std::optional<TransferFunctionEditor> history;
    if (sameData) kept = session->view();
    else if (session->transferEditor()) history = *session->transferEditor();
    session.reset();  // before the data it reads
    data = std::move(*candidate);
    session = makeSession(data);
    if (kept) session->restoreView(*kept);
    if (history) session->continueTransferHistory(*history);
    opened(*next);
  }
}

}  // namespace fcc::render
