// Runs the built `aloha` program (ALOHA_TOOL) with arguments and captures its exit code and output.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace aloha::test {

/// The exit code (-1 when it did not exit normally) and stdout + stderr of one run.
struct RunResult {
    int code = -1;
    std::string output;
};

/// Runs `aloha ARGS` through the shell, stderr merged into the output.
inline RunResult run(const std::string& args) {
    RunResult r;
    const std::string cmd = std::string(ALOHA_TOOL) + " " + args + " 2>&1";
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return r;
    std::array<char, 4096> buf{};
    while (fgets(buf.data(), static_cast<int>(buf.size()), pipe)) r.output += buf.data();
    const int status = pclose(pipe);
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

}  // namespace aloha::test
