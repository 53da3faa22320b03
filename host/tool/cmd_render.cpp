// `aloha render` and `aloha validate` (of a scene, or of one character file).
#include "host/scene/character_report.hpp"
#include "host/scene/character_type.hpp"
#include "host/scene/scene_checks.hpp"
#include "host/scene/scene_loader.hpp"
#include "host/tool/commands.hpp"
#include "host/tool/session.hpp"
#include "systems/lod/rule_table.hpp"

#include <cctype>
#include <filesystem>
#include <iostream>
#include <optional>

namespace aloha::tool {

int run_render(const CliOptions& options) {
    const std::string out = options.out.empty() ? "frame.png" : options.out;
    if (!check_can_write(out, options.force)) return 1;
    auto session = open_session(options, /*render=*/true);
    if (!session.ok()) {
        print_error(session.error().to_string());
        return 1;
    }
    Session& s = *session.value();
    const uint32_t last = options.frame.value_or(s.scene.frames - 1);
    for (uint32_t f = 0; f <= last; ++f) {
        s.world->step();
        if (!s.world->render_status().ok()) {
            print_error(s.world->render_status().error().to_string());
            return 1;
        }
    }
    if (Status st = save_frame(s, out); !st.ok()) {
        print_error(st.error().to_string());
        return 1;
    }
    if (Status v = check_validation(s); !v.ok()) {
        print_error(v.error().to_string());
        return 1;
    }
    std::cout << "wrote frame " << last << " of " << options.scene << " (" << s.world->character_count()
              << " characters, " << s.scene.width << "x" << s.scene.height << ") to " << out << "\n";
    return 0;
}

namespace {

// The character format of `path` from its suffix (.glb, .gltf, .vrm: glTF; .bvh), or "" for anything else (a scene).
std::string character_format(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext == ".glb" || ext == ".gltf" || ext == ".vrm") return "gltf";
    return ext == ".bvh" ? "bvh" : "";
}

// `aloha validate FILE` on a character file: loads it as a scene's character type would (no humanoid_map
// or scale) and prints its report, so a user sees what ALOHA makes of a character before writing a scene.
int validate_character(const std::string& path, const std::string& format) {
    CharacterTypeDesc desc;
    desc.name = std::filesystem::path(path).stem().string();
    (format == "gltf" ? desc.gltf : desc.bvh) = path;
    desc.scene_file = path;
    auto canonical = resolve_scene_path(path, "builtin:humanoid", "");
    if (!canonical.ok()) {
        std::cerr << canonical.error().to_string() << "\n";
        return 1;
    }
    desc.canonical = canonical.value();
    auto type = load_character_type(desc);
    if (!type.ok()) {
        std::cerr << type.error().to_string() << "\n" << path << ": 1 problem(s)\n";
        return 1;
    }
    std::cout << "character type '" << desc.name << "' (" << path << "):\n";
    for (const std::string& line : character_report(type.value())) std::cout << "  " << line << "\n";
    std::cout << path << ": ok (a character file: a scene names it in 'character_types' as {\"" << format << "\": ...}, "
              << "with 'humanoid_map' or 'scale' where the report asks for them)\n";
    return 0;
}

}  // namespace

int run_validate(const CliOptions& options) {
    if (const std::string format = character_format(options.scene); !format.empty()) return validate_character(options.scene, format);
    auto scene = load_scene(options.scene);
    if (!scene.ok()) {
        std::cerr << scene.error().to_string() << "\n";
        return 1;
    }
    int problems = 0;
    std::vector<Error> rule_errors;
    auto rules = load_rules(scene.value().rules, &rule_errors);
    if (!rules.ok()) {
        for (const Error& e : rule_errors.empty() ? std::vector<Error>{rules.error()} : rule_errors)
            std::cerr << e.to_string() << "\n";
        ++problems;
    } else {
        for (const Error& w : rules.value().warnings) std::cerr << "warning: " << w.to_string() << "\n";
    }
    std::vector<std::optional<CharacterType>> loaded;
    std::vector<const CharacterType*> types;
    for (const CharacterTypeDesc& t : scene.value().types) {
        auto type = load_character_type(t);
        loaded.emplace_back();
        if (!type.ok()) {
            std::cerr << type.error().to_string() << "\n";
            ++problems;
        } else {
            std::cout << "character type '" << t.name << "' ("
                      << (t.humanoid.empty() ? (t.bvh.empty() ? t.gltf : t.bvh) : t.humanoid) << "):\n";
            for (const std::string& line : character_report(type.value())) std::cout << "  " << line << "\n";
            loaded.back() = std::move(type).value();
        }
    }
    for (const std::optional<CharacterType>& t : loaded) types.push_back(t ? &*t : nullptr);
    for (const Error& e : scene_request_problems(scene.value(), types)) {
        std::cerr << e.to_string() << "\n";
        ++problems;
    }
    if (problems) {
        std::cerr << options.scene << ": " << problems << " problem(s)\n";
        return 1;
    }
    std::cout << options.scene << ": ok (" << character_count(scene.value()) << " characters, "
              << scene.value().types.size() << " character type(s), rules " << scene.value().rules << ")\n";
    return 0;
}

}  // namespace aloha::tool
