// Render progress for people: a redrawn bar on a terminal, plain lines (at most one every
// few seconds) otherwise, and a final summary line.
#pragma once

#include <cstdio>

#include "embedded/local_render.h"

namespace pf {

class ProgressDisplay {
public:
    // Writes to `out` (stderr by default); detects whether it is a terminal.
    explicit ProgressDisplay(std::FILE* out = stderr);
    void Update(const RenderProgress& progress);
    void Finish(const RenderOutcome& outcome);
    // Ends the bar without a summary (the caller prints its own).
    void Finish();

private:
    std::FILE* out_;
    bool terminal_;
    double last_line_seconds_ = -1e9;
};

}  // namespace pf
