#pragma once
// One exception type for every user-facing failure: its message is the one line the CLI prints
// ("scenes/x.json: models[0].obj: file not found"), so it must name the file and what is wrong.
#include <stdexcept>
#include <string>

namespace lp {

struct Error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace lp
