#pragma once
// Where the viewer keeps per-user files (the panel's layout, imgui.ini): never the working directory.
#include <filesystem>
#include <functional>

namespace lp::app {

// $LIGHTPASS_CONFIG_DIR when set (tests point it at their output), else $XDG_CONFIG_HOME/lightpass
// (an absolute path, as the XDG spec requires), else $HOME/.config/lightpass; empty when none of them
// is set. Reads the environment through getenv so tests can give their own.
std::filesystem::path userConfigDir(const std::function<const char*(const char*)>& getenv);

}  // namespace lp::app
