// Chrome trace output: parses as JSON with one "X" event per system run and thread metadata.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <nlohmann/json.hpp>

#include "engine/scheduler/chrome_trace.hpp"
#include "engine/scheduler/scheduler.hpp"
#include "tests/engine/scheduler/test_phases.hpp"

namespace aloha {
namespace {

TEST(Trace, JsonParsesWithExpectedEvents) {
    Scheduler s(test::test_phases(), 2);
    std::vector<TraceEvent> all;
    s.set_trace_sink([&](const TraceEvent& e) { all.push_back(e); });
    s.add(SystemDesc{"lod \"attributes\"", test::TestPhase::Attributes, {}, {}, [](SystemContext&) {}});
    s.add(SystemDesc{"render", test::TestPhase::Render, {}, {}, [](SystemContext&) {}});
    ASSERT_TRUE(s.build().ok());
    for (int f = 0; f < 3; ++f) s.run_frame(0.01f);
    const std::string path = ::testing::TempDir() + "aloha_trace_test.json";
    const Status st = write_chrome_trace(path, all, s.names());
    ASSERT_TRUE(st.ok()) << st.error().to_string();
    std::ifstream in(path);
    const nlohmann::json j = nlohmann::json::parse(in);
    ASSERT_TRUE(j.contains("traceEvents"));
    std::map<std::string, int> counts;
    int metadata = 0;
    for (const auto& e : j["traceEvents"]) {
        if (e["ph"] == "M") {
            ++metadata;
            continue;
        }
        ASSERT_EQ(e["ph"], "X");
        ++counts[e["name"].get<std::string>()];
        EXPECT_GE(e["dur"].get<double>(), 0.0);
        // No parallel_for here: only whole-system runs, on each system's own track.
        EXPECT_EQ(e["cat"], "system");
        const int system = e["name"] == "render" ? 1 : 0;
        EXPECT_EQ(e["tid"].get<int>(), static_cast<int>(kSystemTrackBase) + system);
        EXPECT_LT(e["args"]["thread"].get<int>(), 2);
    }
    EXPECT_EQ(counts["lod \"attributes\""], 3);  // escaping survived the round trip
    EXPECT_EQ(counts["render"], 3);
    EXPECT_EQ(metadata, 1 + 2 * 2);  // process name + name and sort index of each system track
    std::remove(path.c_str());
}

TEST(Trace, TimesAreMicroseconds) {
    const std::vector<TraceEvent> events{{0, 1, 1'500, 4'000, 7}};
    const std::vector<std::string> names{"sys"};
    const nlohmann::json j = nlohmann::json::parse(chrome_trace_json(events, names));
    const auto& e = j["traceEvents"].back();
    EXPECT_DOUBLE_EQ(e["ts"].get<double>(), 1.5);  // 1500 ns, written exactly with 3 decimals
    EXPECT_DOUBLE_EQ(e["dur"].get<double>(), 2.5);
    EXPECT_EQ(e["tid"], kSystemTrackBase);  // system 0's track
    EXPECT_EQ(e["args"]["thread"], 1);
    EXPECT_EQ(e["args"]["frame"], 7);
}

// GPU passes (TraceKind::Gpu) go on one track of their own, named "GPU passes", category "gpu", named after
// the entry of `names` they index.
TEST(Trace, GpuPassesGetTheirOwnTrack) {
    const std::vector<TraceEvent> events{{0, 0, 1'000, 2'000, 3, TraceKind::System},
                                         {1, 0, 1'200, 1'900, 3, TraceKind::Gpu}};
    const std::vector<std::string> names{"render", "gpu: skinned"};
    const nlohmann::json j = nlohmann::json::parse(chrome_trace_json(events, names));
    bool named = false, seen = false;
    for (const auto& e : j["traceEvents"]) {
        if (e["ph"] == "M" && e["name"] == "thread_name" && e["tid"] == kGpuTrack) named = e["args"]["name"] == "GPU passes";
        if (e["ph"] == "X" && e["name"] == "gpu: skinned") {
            seen = true;
            EXPECT_EQ(e["tid"], kGpuTrack);
            EXPECT_EQ(e["cat"], "gpu");
            EXPECT_DOUBLE_EQ(e["dur"].get<double>(), 0.7);
        }
    }
    EXPECT_TRUE(named);
    EXPECT_TRUE(seen);
}

// A system whose parallel_for keeps both threads busy shows up on its own track and, per frame, on
// one track per thread that ran its chunks, each span inside the system's run.
TEST(Trace, ParallelWorkGetsOneTrackPerThread) {
    Scheduler s(test::test_phases(), 2);
    std::vector<TraceEvent> all;
    s.set_trace_sink([&](const TraceEvent& e) { all.push_back(e); });
    s.add(SystemDesc{"spin", test::TestPhase::Motion, {}, {}, [](SystemContext& ctx) {
                         ctx.parallel_for(64, 1, [](size_t, size_t) {
                             const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(200);
                             while (std::chrono::steady_clock::now() < until) {
                             }
                         });
                     }});
    s.add(SystemDesc{"serial", test::TestPhase::Render, {}, {}, [](SystemContext&) {}});
    ASSERT_TRUE(s.build().ok());
    constexpr int kFrames = 4;
    for (int f = 0; f < kFrames; ++f) s.run_frame(0.01f);
    std::map<uint64_t, TraceEvent> runs;       // frame -> the spin system's run
    std::map<uint64_t, std::set<uint32_t>> workers;  // frame -> threads that did its work
    for (const TraceEvent& e : all)
        if (e.system == 0 && e.kind == TraceKind::System) runs[e.frame] = e;
    for (const TraceEvent& e : all) {
        if (e.kind != TraceKind::Work) continue;
        ASSERT_EQ(e.system, 0u);  // the serial system has no parallel work
        ASSERT_LT(e.thread, 2u);
        EXPECT_TRUE(workers[e.frame].insert(e.thread).second) << "one span per thread per parallel_for";
        ASSERT_TRUE(runs.count(e.frame));
        EXPECT_GE(e.begin_ns, runs[e.frame].begin_ns);
        EXPECT_LE(e.end_ns, runs[e.frame].end_ns);
        EXPECT_LE(e.begin_ns, e.end_ns);
    }
    EXPECT_EQ(workers.size(), static_cast<size_t>(kFrames));
    // 64 chunks of 200 us on two threads: the second thread joins in at least once.
    bool both = false;
    for (const auto& [frame, threads] : workers) both = both || threads.size() == 2;
    EXPECT_TRUE(both);

    const nlohmann::json j = nlohmann::json::parse(chrome_trace_json(all, s.names()));
    std::map<int, std::string> track_names;
    for (const auto& e : j["traceEvents"])
        if (e["name"] == "thread_name") track_names[e["tid"].get<int>()] = e["args"]["name"].get<std::string>();
    EXPECT_EQ(track_names[static_cast<int>(kSystemTrackBase)], "system: spin");
    EXPECT_EQ(track_names[static_cast<int>(kSystemTrackBase) + 1], "system: serial");
    EXPECT_EQ(track_names[0], "worker 0");
    EXPECT_EQ(track_names[1], "worker 1");
    for (const auto& e : j["traceEvents"])
        if (e["ph"] == "X" && e["cat"] == "work") {
            EXPECT_LT(e["tid"].get<int>(), 2);
        }
}

// A sink set after untraced frames gets only its own frames' events, work included (the per-thread
// spans are sized at build, before any sink).
TEST(Trace, SinkSetLaterGetsOnlyItsOwnFrames) {
    Scheduler s(test::test_phases(), 2);
    int calls = 0;
    s.add(SystemDesc{"spin", test::TestPhase::Motion, {}, {}, [&](SystemContext& ctx) {
                         ctx.parallel_for(8, 1, [](size_t, size_t) {});
                         ++calls;
                     }});
    ASSERT_TRUE(s.build().ok());
    s.run_frame(0.01f);
    std::vector<TraceEvent> all;
    s.set_trace_sink([&](const TraceEvent& e) { all.push_back(e); });
    s.run_frame(0.01f);
    EXPECT_EQ(calls, 2);
    ASSERT_FALSE(all.empty());
    for (const TraceEvent& e : all) EXPECT_EQ(e.frame, 1u);  // nothing left over from the untraced frame
    EXPECT_EQ(std::count_if(all.begin(), all.end(), [](const TraceEvent& e) { return e.kind == TraceKind::System; }), 1);
    EXPECT_GE(std::count_if(all.begin(), all.end(), [](const TraceEvent& e) { return e.kind == TraceKind::Work; }), 1);
}

TEST(Trace, UnwritablePathNamesTheFile) {
    const std::string path = "/nonexistent-dir/trace.json";
    const Status st = write_chrome_trace(path, {}, {});
    ASSERT_FALSE(st.ok());
    EXPECT_EQ(st.error().file, path);
    EXPECT_NE(st.error().message.find("cannot open"), std::string::npos);
}

}  // namespace
}  // namespace aloha
