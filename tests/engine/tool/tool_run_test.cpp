// Runs the built `aloha` program end to end (headless, lavapipe) and checks its outputs and errors.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

struct RunResult {
    int code = -1;
    std::string output;
};

RunResult run(const std::string& args) {
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

const std::string kScenes = std::string(ALOHA_SOURCE_DIR) + "/data/scenes/";

fs::path temp_dir(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("aloha_tool_" + name);
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

TEST(Tool, ProfileWritesEveryReport) {
    const fs::path out = temp_dir("profile");
    const RunResult r = run("profile " + kScenes + "crowd_1k.json --frames 6 --warmup 2 --characters 200 --quiet "
                            "--validation --out " + (out / "p").string());
    ASSERT_EQ(r.code, 0) << r.output;
    for (const char* f : {"report.json", "frames.csv", "trace.json", "frame_times.svg", "last_frame.png"})
        EXPECT_TRUE(fs::exists(out / "p" / f)) << f;
    std::ifstream in(out / "p" / "report.json");
    const nlohmann::json report = nlohmann::json::parse(in);
    EXPECT_EQ(report["characters"], 200);
    EXPECT_EQ(report["frames"], 6);
    for (const char* k : {"mean", "p50", "p95", "p99", "max"}) {
        EXPECT_TRUE(report["cpu_systems_ms"].contains(k));
        EXPECT_TRUE(report["systems"]["lod_rules"].contains(k));
    }
    EXPECT_EQ(report["characters_per_level_per_frame"].size(), 6u);
    // frames.csv: a header of distinct column names (per-system columns apart from the totals), then
    // one row per measured frame with as many fields.
    std::ifstream csv(out / "p" / "frames.csv");
    std::vector<std::vector<std::string>> rows;
    for (std::string line; std::getline(csv, line);) {
        std::vector<std::string> fields;
        std::stringstream ss(line);
        for (std::string field; std::getline(ss, field, ',');) fields.push_back(field);
        rows.push_back(std::move(fields));
    }
    ASSERT_EQ(rows.size(), 7u);
    const std::set<std::string> columns(rows[0].begin(), rows[0].end());
    EXPECT_EQ(columns.size(), rows[0].size()) << "duplicate column names";
    EXPECT_TRUE(columns.count("render_ms") && columns.count("system_render_ms") && columns.count("system_motion_ms"));
    for (const auto& row : rows) EXPECT_EQ(row.size(), rows[0].size());
    // trace.json: one track per system, and per worker thread that ran a system's parallel work.
    std::ifstream trace(out / "p" / "trace.json");
    const nlohmann::json t = nlohmann::json::parse(trace);
    EXPECT_FALSE(t["traceEvents"].empty());
    std::set<std::string> tracks;
    for (const auto& e : t["traceEvents"])
        if (e["name"] == "thread_name") tracks.insert(e["args"]["name"].get<std::string>());
    for (const char* track : {"system: lod_attributes", "system: motion", "system: muscle", "system: spring_skin", "system: render", "worker 0"})
        EXPECT_TRUE(tracks.count(track)) << track;
    EXPECT_EQ(r.output.find("Validation"), std::string::npos) << r.output;
    // A second run refuses to overwrite the reports without --force.
    const RunResult again = run("profile " + kScenes + "crowd_1k.json --frames 2 --characters 50 --quiet --out " + (out / "p").string());
    EXPECT_NE(again.code, 0);
    EXPECT_NE(again.output.find("--force"), std::string::npos) << again.output;
    fs::remove_all(out);
}

TEST(Tool, RenderWritesAPngAndRefusesToOverwrite) {
    const fs::path out = temp_dir("render");
    const std::string png = (out / "f.png").string();
    const RunResult r = run("render " + kScenes + "crowd_1k.json --frame 3 --characters 100 --out " + png);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_GT(fs::file_size(png), 1000u);
    const RunResult again = run("render " + kScenes + "crowd_1k.json --frame 1 --characters 100 --out " + png);
    EXPECT_NE(again.code, 0);
    fs::remove_all(out);
}

TEST(Tool, ValidateReportsBadScenesAndPassesGoodOnes) {
    const RunResult good = run("validate " + kScenes + "closeup.json");
    EXPECT_EQ(good.code, 0) << good.output;
    const fs::path out = temp_dir("validate");
    {
        std::ofstream f(out / "bad.json");
        f << R"({"camera": {"position": [0, 1, 5], "target": [0, 1, 0]}, "crowds": [{"count": 1e9}]})";
    }
    const RunResult bad = run("validate " + (out / "bad.json").string());
    EXPECT_EQ(bad.code, 1);
    EXPECT_NE(bad.output.find("bad.json"), std::string::npos) << bad.output;
    EXPECT_NE(bad.output.find("/crowds/0/count"), std::string::npos) << bad.output;
    const RunResult usage = run("profile --frames x");
    EXPECT_EQ(usage.code, 2);
    fs::remove_all(out);
}

}  // namespace

namespace {

// Reads a CSV written by `aloha export` (no quoted fields in the built-in scenes) into rows of fields.
std::vector<std::vector<std::string>> read_csv(const fs::path& path) {
    std::ifstream in(path);
    std::vector<std::vector<std::string>> rows;
    std::string line;
    while (std::getline(in, line)) {
        std::vector<std::string> fields;
        std::stringstream ss(line);
        std::string f;
        while (std::getline(ss, f, ',')) fields.push_back(f);
        rows.push_back(std::move(fields));
    }
    return rows;
}

}  // namespace

// Export: every joint of the chosen characters on the chosen frames, with level and method; the same
// positions as a second run (deterministic); refuses to overwrite; bad selections are named.
TEST(Tool, ExportWritesJointsOfTheChosenCharactersAndFrames) {
    const fs::path out = temp_dir("export");
    const std::string csv = (out / "joints.csv").string();
    const RunResult r = run("export " + kScenes + "crowd_1k.json --joints " + csv + " --characters 3,10-11 --frames 4:7");
    ASSERT_EQ(r.code, 0) << r.output;
    const auto rows = read_csv(csv);
    ASSERT_GT(rows.size(), 1u);
    const std::vector<std::string> header = {"frame", "time_s", "character", "type", "id", "anim_level", "level_index",
                                             "update_interval", "method", "in_transition", "joint", "joint_name", "x", "y", "z"};
    EXPECT_EQ(rows[0], header);
    std::set<std::string> characters, frames;
    size_t per_character_frame = 0;
    for (size_t i = 1; i < rows.size(); ++i) {
        ASSERT_EQ(rows[i].size(), header.size()) << "row " << i;
        characters.insert(rows[i][2]);
        frames.insert(rows[i][0]);
        if (rows[i][2] == "3" && rows[i][0] == "4") ++per_character_frame;
        EXPECT_TRUE(rows[i][8] == "clip" || rows[i][8] == "kinematic" || rows[i][8] == "dynamic" ||
                    rows[i][8] == "play_clip" || rows[i][8] == "rest") << rows[i][8];
    }
    EXPECT_EQ(characters, (std::set<std::string>{"3", "10", "11"}));
    EXPECT_EQ(frames, (std::set<std::string>{"4", "5", "6"}));
    EXPECT_EQ(rows.size() - 1, 3 * 3 * per_character_frame);  // every joint of each character on each frame
    const RunResult again = run("export " + kScenes + "crowd_1k.json --joints " + csv + " --characters 3,10-11 --frames 4:7");
    EXPECT_NE(again.code, 0);
    EXPECT_NE(again.output.find("already exists"), std::string::npos) << again.output;
    const std::string csv2 = (out / "joints2.csv").string();
    ASSERT_EQ(run("export " + kScenes + "crowd_1k.json --joints " + csv2 + " --characters 3,10-11 --frames 4:7").code, 0);
    EXPECT_EQ(read_csv(csv2), rows);
    const RunResult past = run("export " + kScenes + "crowd_1k.json --joints " + (out / "x.csv").string() + " --characters 5000");
    EXPECT_EQ(past.code, 2);
    EXPECT_NE(past.output.find("character 5000"), std::string::npos) << past.output;
    EXPECT_FALSE(fs::exists(out / "x.csv"));
}

// --motion-metrics: report.json carries per-level figures and the bars; the table is printed.
TEST(Tool, ProfileMotionMetricsReportsSkateAndPopsPerLevel) {
    const fs::path out = temp_dir("motion_metrics");
    const RunResult r = run("profile " + kScenes + "crowd_1k.json --no-render --motion-metrics --frames 60 --warmup 2 "
                            "--characters 100 --quiet --out " + (out / "p").string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("motion metrics"), std::string::npos) << r.output;
    std::ifstream in(out / "p" / "report.json");
    const nlohmann::json m = nlohmann::json::parse(in)["motion_metrics"];
    ASSERT_TRUE(m.is_object());
    EXPECT_EQ(m["skate_bar_mm_per_m"], 10.0);
    EXPECT_NEAR(m["contact"]["height_m"].get<double>(), 0.005, 1e-9);  // a float in the report
    ASSERT_FALSE(m["per_level_and_interval"].empty());
    double walked = 0.0;
    for (const auto& b : m["per_level_and_interval"]) {
        for (const char* k : {"anim_level", "update_interval", "walked_m", "skate_mm_per_m", "switch_frames",
                              "worst_switch_cm", "ordinary_p95_cm", "transition_frames", "worst_transition_cm"})
            EXPECT_TRUE(b.contains(k)) << k;
        walked += b["walked_m"].get<double>();
    }
    EXPECT_NEAR(m["overall"]["walked_m"].get<double>(), walked, 1e-6 * walked);
    EXPECT_GT(walked, 0.0);  // the crowd walks
}
