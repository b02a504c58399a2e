#include "app/pass_rows.hpp"

#include <algorithm>

namespace lp::app {
namespace {

std::string withoutPrefix(const std::string& text, const std::string& prefix) {
    return text.compare(0, prefix.size(), prefix) == 0 ? text.substr(prefix.size()) : text;
}

}  // namespace

const char* passRowStateName(PassRowState state) {
    switch (state) {
        case PassRowState::Runs: return "runs";
        case PassRowState::Culled: return "culled";
        case PassRowState::Skipped: return "skipped";
        case PassRowState::Off: return "off";
        case PassRowState::Absent: return "not in this frame";
    }
    return "?";
}

void updatePassRows(std::vector<PassRow>& rows, const std::vector<fg::PassDecision>& decisions,
                    const std::set<std::string>& disabledPasses) {
    for (PassRow& row : rows) {
        row.state = PassRowState::Absent;
        row.reason = "not a candidate in this view or with these settings";
    }
    std::set<std::string> seenThisFrame;
    size_t insertAt = 0;  // just after the row of the pass considered before
    for (const fg::PassDecision& d : decisions) {
        auto it = std::find_if(rows.begin(), rows.end(), [&](const PassRow& r) { return r.name == d.name; });
        if (it == rows.end()) {
            PassRow added;
            added.name = d.name;
            it = rows.insert(rows.begin() + std::ptrdiff_t(std::min(insertAt, rows.size())), added);
        }
        insertAt = size_t(it - rows.begin()) + 1;
        PassRow& row = *it;
        // A name added twice in one frame (upscale of the HDR image and of a debug view) is one
        // switch: it runs if either copy runs.
        const bool again = !seenThisFrame.insert(d.name).second;
        if (again && (row.state == PassRowState::Runs || row.state == PassRowState::Off)) continue;
        if (disabledPasses.count(d.name)) {
            row.state = PassRowState::Off;
            row.reason = d.reason;
        } else if (d.runs) {
            row.state = PassRowState::Runs;
            row.reason.clear();
        } else if (d.reason.compare(0, 9, "skipped: ") == 0) {
            row.state = PassRowState::Skipped;
            row.reason = withoutPrefix(d.reason, "skipped: ");
        } else {
            row.state = PassRowState::Culled;
            row.reason = withoutPrefix(d.reason, "culled: ");
        }
    }
}

}  // namespace lp::app
