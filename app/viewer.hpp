#pragma once
#include "app/cli.hpp"

namespace lp::app {
// The interactive window: seed 001's keys, a fly camera, the ImGui panel (app/viewer_panel.cpp),
// scene/environment pickers and shader hot reload.
int runViewer(const Options& options);
}
