// aloha: the command-line tool (render, view, profile, validate).
#include "host/scene/scene_loader.hpp"
#include "host/tool/commands.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>

namespace aloha::tool {

void print_error(const std::string& message) { std::cerr << "aloha: " << message << "\n"; }

bool check_can_write(const std::string& path, bool force) {
    std::error_code ec;
    if (!force && std::filesystem::exists(path, ec)) {
        print_error(path + " already exists; pass --force to overwrite it");
        return false;
    }
    return true;
}

// The data folder when $ALOHA_DATA_DIR is unset: share/aloha beside an installed tool (bin/../share/aloha),
// else the source tree this tool was built from (ALOHA_BUILD_TREE_DATA_DIR, the tool's own definition;
// the installed libraries never carry a source path).
void choose_data_directory() {
    if (const char* env = std::getenv("ALOHA_DATA_DIR"); env && *env) return;
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    const fs::path installed = exe.parent_path() / ".." / "share" / "aloha";
    if (!ec && fs::exists(installed / "characters" / "humanoid.json", ec))
        aloha::set_data_directory(installed.lexically_normal().string());
    else
        aloha::set_data_directory(ALOHA_BUILD_TREE_DATA_DIR);
}

}  // namespace aloha::tool

int main(int argc, char** argv) {
    using namespace aloha::tool;
    choose_data_directory();
    std::vector<std::string> args(argv + 1, argv + argc);
    auto parsed = parse_cli(args);
    if (!parsed.ok()) {
        print_error(parsed.error().to_string());
        std::cerr << "try 'aloha --help'\n";
        return 2;
    }
    const CliOptions& o = parsed.value();
    if (o.command == "help") {
        std::cout << help_text(o.scene);
        return 0;
    }
    if (o.help) {
        std::cout << help_text(o.command);
        return 0;
    }
    if (o.command == "render") return run_render(o);
    if (o.command == "validate") return run_validate(o);
    if (o.command == "profile") return run_profile(o);
    if (o.command == "view") return run_view(o);
    if (o.command == "scale") return run_scale(o);
    if (o.command == "export") return run_export(o);
    print_error("unknown command '" + o.command + "'");
    return 2;
}
