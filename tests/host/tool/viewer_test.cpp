// `aloha view`: the free cameras' maths, live rule editing (edits equal what the parser makes of the
// edited file; reload keeps character state), and the built tool run under a private Xvfb: 20 frames
// with --validation and --out (exit 0, PNG of the window's size that is not flat, no validation
// message), and a bad scene failing with the file named.
#include "engine/gpu/png.hpp"
#include "host/tool/viewer_camera.hpp"
#include "host/tool/viewer_pick.hpp"
#include "host/tool/viewer_rules.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cfloat>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <thread>

#include <sys/wait.h>
#include <unistd.h>

namespace aloha::tool {
namespace {

namespace fs = std::filesystem;

// Float trigonometry of arguments of order 1 is accurate to a few ulp (~1e-7 relative); positions
// built from it on metre scales agree to well under 1e-5 m.
constexpr float kTrig = 1e-6f;
constexpr float kPos = 1e-5f;

void expect_near(glm::vec3 a, glm::vec3 b, float tol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

TEST(ViewerCamera, AnglesGiveTheAxes) {
    expect_near(direction_from_angles(0.0f, 0.0f), {0, 0, 1}, kTrig);
    expect_near(direction_from_angles(glm::half_pi<float>(), 0.0f), {1, 0, 0}, kTrig);
    expect_near(direction_from_angles(0.3f, glm::half_pi<float>()), {0, 1, 0}, kTrig);
}

TEST(ViewerCamera, ResetFromKeyReproducesTheScenePlacement) {
    CameraDesc desc;
    desc.fov_y_deg = 45.0f;
    const CameraKey key{0.0f, {2.2f, 1.5f, 3.2f}, {0.0f, 0.95f, 0.0f}};
    ViewerCamera cam;
    cam.reset_from(desc, key);
    EXPECT_EQ(cam.fov_y_deg, 45.0f);
    expect_near(cam.orbit.eye(), key.position, kPos);
    EXPECT_EQ(cam.fly.position, key.position);
    expect_near(cam.fly.forward(), glm::normalize(key.target - key.position), kTrig);
    // Switching mode does not jump: every mode looks from the same eye along the same line.
    for (CameraMode m : {CameraMode::ScenePath, CameraMode::Orbit, CameraMode::Fly}) {
        cam.mode = m;
        const CameraKey p = cam.placement(key);
        expect_near(p.position, key.position, kPos);
        expect_near(glm::normalize(p.target - p.position), glm::normalize(key.target - key.position), kPos);
    }
}

TEST(ViewerCamera, OrbitViewPutsTheTargetOnTheAxis) {
    ViewerCamera cam;
    cam.mode = CameraMode::Orbit;
    cam.orbit = OrbitCamera{{1.0f, 2.0f, -3.0f}, 0.7f, -0.4f, 6.0f};
    const RenderCamera rc = cam.matrices(CameraKey{}, 16.0f / 9.0f);
    const glm::vec4 v = rc.view * glm::vec4(cam.orbit.target, 1.0f);
    // Distance 6 m, rotation error ~1e-7 per component -> < 1e-5 m.
    expect_near(glm::vec3(v), {0.0f, 0.0f, -6.0f}, kPos * 6.0f);
}

TEST(ViewerCamera, OrbitTurnsKeepDistanceAndClampPitch) {
    OrbitCamera o{{0.0f, 1.0f, 0.0f}, 0.0f, 0.0f, 4.0f};
    o.rotate(123.0f, 45.0f);
    EXPECT_NEAR(glm::length(o.eye() - o.target), 4.0f, kPos * 4.0f);
    o.rotate(0.0f, 1.0e6f);  // drag far down: pitch stops just short of vertical
    EXPECT_EQ(o.pitch, kMaxPitch);
    o.zoom(1.0f);
    EXPECT_NEAR(o.distance, 3.6f, 3.6f * kTrig);  // one notch = x0.9 (pow of float: ~1 ulp)
    o.zoom(-1.0e4f);
    EXPECT_EQ(o.distance, 2000.0f);
}

TEST(ViewerCamera, FlyMovesAtItsSpeed) {
    FlyCamera f;
    f.position = {0, 1, 0};
    f.yaw = 0.5f;
    f.pitch = 0.2f;
    f.speed = 3.0f;
    const glm::vec3 start = f.position;
    f.move({0, 0, 1}, 0.5f);  // forward for half a second: 1.5 m along forward()
    expect_near(f.position - start, 1.5f * f.forward(), kPos);
    const glm::vec3 before = f.position;
    f.move({1, 0, 0}, 1.0f, 2.0f);  // strafe right, boosted: 6 m, horizontal, perpendicular to forward
    const glm::vec3 d = f.position - before;
    EXPECT_NEAR(glm::length(d), 6.0f, 6.0f * kTrig * 4.0f);
    EXPECT_NEAR(d.y, 0.0f, kPos);
    EXPECT_NEAR(glm::dot(d, f.forward()), 0.0f, kPos * 6.0f);
}

// A small rule file: three geometric levels, one rule with a two-sided distance range.
std::string small_rules(int geom_levels, float near_hi) {
    nlohmann::json j;
    j["hysteresis"] = {{"band", 0.1}, {"min_seconds", 0.08}};
    j["geometric_levels"] = nlohmann::json::array();
    for (int i = 0; i < geom_levels; ++i)
        j["geometric_levels"].push_back({{"name", "g" + std::to_string(i)}, {"method", "rigid_proxy"}});
    j["animation_levels"] = {{{"name", "clip"}, {"walk", "clip"}}};
    j["rules"] = {{{"name", "near"}, {"when", {{"distance", {{"ge", 10.0}, {"le", near_hi}}}, {"visible", true}}},
                   {"then", {{"geometry", "g1"}, {"animation", "clip"}}}},
                  {{"name", "rest"}, {"then", {{"geometry", "g" + std::to_string(geom_levels - 1)}, {"animation", "clip"}}}}};
    return j.dump();
}

RuleTable parse_ok(const std::string& text) {
    Result<RuleTable> t = parse_rules(text, "test.json");
    EXPECT_TRUE(t.ok()) << (t.ok() ? "" : t.error().to_string());
    return t.ok() ? std::move(t).value() : RuleTable{};
}

// Box-by-box bitwise equality: the viewer uses the parser's formula, so the floats are identical.
void expect_same_boxes(const RuleTable& a, const RuleTable& b) {
    ASSERT_EQ(a.boxes.size(), b.boxes.size());
    for (size_t i = 0; i < a.boxes.size(); ++i) {
        EXPECT_EQ(a.boxes[i].lo, b.boxes[i].lo) << "box " << i;
        EXPECT_EQ(a.boxes[i].hi, b.boxes[i].hi) << "box " << i;
        EXPECT_EQ(a.boxes[i].lo_wide, b.boxes[i].lo_wide) << "box " << i;
        EXPECT_EQ(a.boxes[i].hi_wide, b.boxes[i].hi_wide) << "box " << i;
    }
}

TEST(ViewerRules, HysteresisEditEqualsTheParsedFile) {
    std::ifstream in(std::string(ALOHA_SOURCE_DIR) + "/data/rules/default.json");
    ASSERT_TRUE(in.good());
    std::stringstream ss;
    ss << in.rdbuf();
    RuleTable edited = parse_ok(ss.str());
    nlohmann::json j = nlohmann::json::parse(ss.str(), nullptr, true, /*ignore_comments=*/true);
    j["hysteresis"]["band"] = 0.25;
    j["hysteresis"]["min_seconds"] = 0.05;
    const RuleTable expected = parse_ok(j.dump());
    set_hysteresis(edited, 0.25f, 0.05f);
    EXPECT_EQ(edited.hysteresis.min_seconds, 0.05f);
    EXPECT_EQ(edited.hysteresis.min_seconds, expected.hysteresis.min_seconds);
    expect_same_boxes(edited, expected);
    EXPECT_TRUE(validate_edited_table(edited));
}

TEST(ViewerRules, ThresholdEditEqualsTheParsedFileAndKeepsBoxesNonEmpty) {
    RuleTable t = parse_ok(small_rules(3, 50.0f));
    const std::vector<RuleThreshold> th = editable_thresholds(t);
    ASSERT_EQ(th.size(), 2u);  // distance lo and hi; "visible" is discrete, "rest" has none
    EXPECT_EQ(th[0].attribute, LodAttribute::Distance);
    EXPECT_FALSE(th[0].upper);
    EXPECT_TRUE(th[1].upper);
    EXPECT_EQ(threshold_value(t, th[1]), 50.0f);
    EXPECT_EQ(set_threshold(t, th[1], 70.0f), 70.0f);
    expect_same_boxes(t, parse_ok(small_rules(3, 70.0f)));
    EXPECT_EQ(set_threshold(t, th[0], 80.0f), 70.0f);   // lower bound may not pass the upper one
    EXPECT_EQ(set_threshold(t, th[1], 5.0f), 70.0f);    // nor the upper the lower (lo is 70 now)
    EXPECT_EQ(set_threshold(t, th[1], std::numeric_limits<float>::infinity()), FLT_MAX);  // stays editable
    EXPECT_EQ(set_threshold(t, th[0], std::nanf("")), 70.0f);  // NaN ignored
    EXPECT_TRUE(validate_edited_table(t));
}

TEST(ViewerRules, ApplyRejectsBrokenTablesAndSwapsValidOnes) {
    RuleSet set;
    set.set_table(parse_ok(small_rules(3, 50.0f)));
    const uint32_t gen = set.generation();
    RuleTable bad = set.table();
    set_rule_levels(bad, 0, 7, 0);  // no level 7
    std::vector<std::string> errors;
    EXPECT_FALSE(validate_edited_table(bad, &errors));
    ASSERT_FALSE(errors.empty());
    EXPECT_NE(errors[0].find("near"), std::string::npos) << errors[0];
    EXPECT_FALSE(apply_edited_table(set, bad).ok());
    EXPECT_EQ(set.generation(), gen);
    RuleTable no_fallback = set.table();
    no_fallback.boxes.back().lo[0] = 1.0f;  // the last rule gains a condition
    EXPECT_FALSE(validate_edited_table(no_fallback));
    RuleTable good = set.table();
    set_rule_levels(good, 0, 2, 0);
    ASSERT_TRUE(apply_edited_table(set, good).ok());
    EXPECT_EQ(set.generation(), gen + 1);
    EXPECT_EQ(set.table().compiled[0].geom_level, 2);
}

TEST(ViewerRules, ReloadRestoresTheFileAndOnlyClampsState) {
    const fs::path path = fs::temp_directory_path() / ("aloha_viewer_rules_" + std::to_string(getpid()) + ".json");
    { std::ofstream(path) << small_rules(3, 50.0f); }
    RuleSet set;
    ASSERT_TRUE(set.load(path.string()).ok());
    RuleTable edited = set.table();
    (void)set_threshold(edited, editable_thresholds(edited)[1], 99.0f);
    ASSERT_TRUE(apply_edited_table(set, edited).ok());
    { std::ofstream(path) << small_rules(2, 50.0f); }  // one geometric level fewer
    std::vector<LodState> states(3);
    states[0].geom_level = 2;
    states[0].seconds_at_geom = 17.0f;
    states[1].geom_level = 1;
    states[1].crossfade_left_s = 0.25f;
    ASSERT_TRUE(reload_rules_keep_state(set, states).ok());
    EXPECT_EQ(threshold_value(set.table(), editable_thresholds(set.table())[1]), 50.0f);
    EXPECT_EQ(states[0].geom_level, 1);       // clamped into the 2-level table
    EXPECT_EQ(states[0].seconds_at_geom, 17.0f);  // timers untouched
    EXPECT_EQ(states[1].geom_level, 1);
    EXPECT_EQ(states[1].crossfade_left_s, 0.25f);
    { std::ofstream(path) << "{ broken"; }
    const uint32_t gen = set.generation();
    EXPECT_FALSE(reload_rules_keep_state(set, states).ok());
    EXPECT_EQ(set.generation(), gen);  // old table kept
    fs::remove(path);
}

// Three characters 1.8 m tall at x = -1, 0, 1 seen from z = 5 with a 90 degree lens on 800 x 600 px:
// at depth 5 one metre is 300 / 5 = 60 px (half-height 300 px over tan 45 deg * 5 m), so neighbours
// are 60 px apart on screen.
struct PickScene {
    std::vector<Transform> transforms{3};
    std::vector<Bounds> bounds{3};
    RenderCamera camera;
    glm::vec2 viewport{800.0f, 600.0f};
    PickScene() {
        for (int i = 0; i < 3; ++i) transforms[size_t(i)].position = {float(i - 1), 0.0f, 0.0f};
        camera.view = glm::lookAt(glm::vec3(0, 0.9f, 5), glm::vec3(0, 0.9f, 0), glm::vec3(0, 1, 0));
        camera.proj = glm::perspective(glm::half_pi<float>(), 800.0f / 600.0f, 0.1f, 100.0f);
    }
};

TEST(ViewerPick, ProjectsToPixelsAndPicksTheNearestAxis) {
    PickScene s;
    glm::vec2 px;
    ASSERT_TRUE(project_to_pixels(s.camera, s.viewport, {1.0f, 0.9f, 0.0f}, &px));
    expect_near({px, 0.0f}, {460.0f, 300.0f, 0.0f}, 1e-3f);  // centre (400, 300) + 60 px right
    EXPECT_FALSE(project_to_pixels(s.camera, s.viewport, {0.0f, 0.9f, 10.0f}, &px));  // behind the eye
    // Feet are 0.9 m below the centre line (row 354), heads 0.9 m above (row 246). A click 10 px right
    // of the right character's axis at row 330 picks it; 25 px off the
    // middle one (between it and its neighbours' 35 px) picks the middle one.
    EXPECT_EQ(pick_character(s.transforms, s.bounds, s.camera, s.viewport, {470.0f, 330.0f}, 40.0f), 2);
    EXPECT_EQ(pick_character(s.transforms, s.bounds, s.camera, s.viewport, {375.0f, 250.0f}, 40.0f), 1);
    // Above every head (1.8 m -> 0.9 m above the centre line = 54 px: row 246) by 100 px: nothing.
    EXPECT_EQ(pick_character(s.transforms, s.bounds, s.camera, s.viewport, {400.0f, 146.0f}, 40.0f), -1);
    s.transforms[1].position.z = 6.0f;  // behind the eye now: never picked
    EXPECT_EQ(pick_character(s.transforms, s.bounds, s.camera, s.viewport, {400.0f, 300.0f}, 40.0f), -1);
}

TEST(ViewerPick, FindsCharactersByRefAndBoxesThem) {
    const std::vector<CharacterRef> refs = {{0, 4}, {1, 4}, {0, 2}};
    EXPECT_EQ(find_character(refs, {1, 4}), 1);
    EXPECT_EQ(find_character(refs, {0, 2}), 2);
    EXPECT_EQ(find_character(refs, {1, 2}), -1);
    std::vector<LineSegment> lines;
    Transform t;
    t.position = {2.0f, 0.0f, -1.0f};
    t.scale = 2.0f;
    marker_lines(t, Bounds{1.8f, 0.4f}, glm::vec4(1.0f), lines);
    ASSERT_EQ(lines.size(), 12u);  // a box's edges
    for (const LineSegment& l : lines)
        for (glm::vec3 p : {l.a, l.b}) {
            EXPECT_NEAR(std::fabs(p.x - 2.0f), 0.8f, 1e-6f);  // radius 0.4 x scale 2
            EXPECT_NEAR(std::fabs(p.z + 1.0f), 0.8f, 1e-6f);
            EXPECT_TRUE(p.y == 0.0f || std::fabs(p.y - 3.6f) < 1e-6f);  // height 1.8 x scale 2
        }
}

#ifdef ALOHA_TOOL_BINARY

// Runs `command` (stderr merged) and returns (exit code, output).
std::pair<int, std::string> run(const std::string& command) {
    std::string out;
    FILE* p = popen((command + " 2>&1").c_str(), "r");
    if (p == nullptr) return {-1, "popen failed"};
    char buf[4096];
    size_t n = 0;
    while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
    const int status = pclose(p);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

// A private X server on a free display number; killed when the object goes.
struct Xvfb {
    pid_t pid = -1;
    int display = -1;
    Xvfb() {
        for (int n = 90 + getpid() % 200; n < 600; ++n) {
            if (fs::exists("/tmp/.X" + std::to_string(n) + "-lock") ||
                fs::exists("/tmp/.X11-unix/X" + std::to_string(n)))
                continue;
            display = n;
            break;
        }
        if (display < 0) return;
        pid = fork();
        if (pid == 0) {
            const std::string d = ":" + std::to_string(display);
            execlp("Xvfb", "Xvfb", d.c_str(), "-screen", "0", "1280x720x24", "-nolisten", "tcp", static_cast<char*>(nullptr));
            _exit(127);
        }
        const std::string socket = "/tmp/.X11-unix/X" + std::to_string(display);
        for (int i = 0; i < 100 && pid > 0 && !fs::exists(socket); ++i)
            std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    bool ready() const { return pid > 0 && fs::exists("/tmp/.X11-unix/X" + std::to_string(display)); }
    ~Xvfb() {
        if (pid > 0) {
            kill(pid, SIGTERM);
            waitpid(pid, nullptr, 0);
        }
    }
};

bool have_xvfb() { return run("command -v Xvfb").first == 0; }

TEST(ViewerTool, TwentyFramesUnderXvfbSaveANonFlatFrameWithoutValidationMessages) {
    if (!have_xvfb()) GTEST_SKIP() << "Xvfb is not installed";
    Xvfb server;
    ASSERT_TRUE(server.ready()) << "Xvfb did not start on :" << server.display;
    const fs::path png = fs::temp_directory_path() / ("aloha_view_" + std::to_string(getpid()) + ".png");
    fs::remove(png);
    const std::string cmd = "DISPLAY=:" + std::to_string(server.display) + " " + ALOHA_TOOL_BINARY + " view " +
                            ALOHA_SOURCE_DIR + "/data/scenes/closeup.json --frames 20 --out " + png.string() +
                            " --validation";
    const auto [code, output] = run(cmd);
    EXPECT_EQ(code, 0) << output;
    for (const char* word : {"validation", "Validation", "VUID"})
        EXPECT_EQ(output.find(word), std::string::npos) << output;
    Result<gpu::Rgba8Image> img = gpu::read_png(png.string());
    ASSERT_TRUE(img.ok()) << img.error().to_string();
    EXPECT_EQ(img.value().width, 1280u);  // closeup.json's viewport = the window
    EXPECT_EQ(img.value().height, 720u);
    // Not flat: the overlay's text and the shaded character give many distinct colours; the right part
    // of the frame (x >= 460, right of the overlay's 440 px panel at x = 10) must show the crowd too.
    const gpu::Rgba8Image& im = img.value();
    std::set<uint32_t> colours;
    std::set<uint32_t> right_colours;
    for (uint32_t y = 0; y < im.height; ++y)
        for (uint32_t x = 0; x < im.width; ++x) {
            const uint8_t* p = &im.pixels[(size_t(y) * im.width + x) * 4];
            const uint32_t c = p[0] | (p[1] << 8) | (p[2] << 16);
            colours.insert(c);
            if (x >= 460) right_colours.insert(c);
        }
    EXPECT_GE(colours.size(), 16u);
    EXPECT_GE(right_colours.size(), 4u) << "nothing drawn outside the overlay";
    fs::remove(png);
}

TEST(ViewerTool, BadSceneFailsNamingTheFile) {
    const fs::path bad = fs::temp_directory_path() / ("aloha_view_bad_" + std::to_string(getpid()) + ".json");
    { std::ofstream(bad) << "{ \"name\": \"broken\", \"characters\": [ }"; }
    const auto [code, output] = run(std::string(ALOHA_TOOL_BINARY) + " view " + bad.string() + " --frames 1");
    EXPECT_NE(code, 0);
    EXPECT_NE(output.find(bad.string()), std::string::npos) << output;
    fs::remove(bad);
    const auto [code2, output2] = run(std::string(ALOHA_TOOL_BINARY) + " view /nonexistent/scene.json --frames 1");
    EXPECT_NE(code2, 0);
    EXPECT_NE(output2.find("/nonexistent/scene.json"), std::string::npos) << output2;
}

#endif  // ALOHA_TOOL_BINARY

}  // namespace
}  // namespace aloha::tool
