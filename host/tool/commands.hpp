// The aloha subcommands. Each returns the process exit code (0 success, 1 failure, 2 usage).
#pragma once

#include "host/tool/cli_args.hpp"

namespace aloha::tool {

struct Session;

/// `aloha render SCENE --frame N --out frame.png`
int run_render(const CliOptions& options);
/// `aloha validate SCENE`
int run_validate(const CliOptions& options);
/// `aloha profile SCENE ...`
int run_profile(const CliOptions& options);
/// `aloha scale SCENE --counts ...`
int run_scale(const CliOptions& options);
/// `aloha export SCENE --joints FILE.csv [--characters LIST] [--frames A:B]`
int run_export(const CliOptions& options);
/// `aloha export SCENE --frame N --character I [--level L] --out FILE.glb` on the session run_export
/// opened (cmd_export_skin.cpp)
int export_skin(const CliOptions& options, Session& session);
/// `aloha view SCENE` (GLFW window with overlay)
int run_view(const CliOptions& options);

/// Prints an error to stderr prefixed with "aloha: ".
void print_error(const std::string& message);

/// Fails when `path` exists and `force` is false (nothing the user has is overwritten silently).
bool check_can_write(const std::string& path, bool force);

}  // namespace aloha::tool
