// Chrome trace output: parses as JSON with one "X" event per system run and thread metadata.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "engine/scheduler/chrome_trace.hpp"
#include "engine/scheduler/scheduler.hpp"

namespace aloha {
namespace {

TEST(Trace, JsonParsesWithExpectedEvents) {
    Scheduler s(2);
    std::vector<TraceEvent> all;
    s.set_trace_sink([&](const TraceEvent& e) { all.push_back(e); });
    s.add(SystemDesc{"lod \"attributes\"", Phase::Attributes, {}, {}, [](SystemContext&) {}});
    s.add(SystemDesc{"render", Phase::Render, {}, {}, [](SystemContext&) {}});
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
        EXPECT_GE(e["tid"].get<int>(), 0);
        EXPECT_LT(e["tid"].get<int>(), 2);
    }
    EXPECT_EQ(counts["lod \"attributes\""], 3);  // escaping survived the round trip
    EXPECT_EQ(counts["render"], 3);
    EXPECT_GE(metadata, 2);  // process name + at least one thread name
    std::remove(path.c_str());
}

TEST(Trace, TimesAreMicroseconds) {
    const std::vector<TraceEvent> events{{0, 1, 1'500, 4'000, 7}};
    const std::vector<std::string> names{"sys"};
    const nlohmann::json j = nlohmann::json::parse(chrome_trace_json(events, names));
    const auto& e = j["traceEvents"].back();
    EXPECT_DOUBLE_EQ(e["ts"].get<double>(), 1.5);  // 1500 ns, written exactly with 3 decimals
    EXPECT_DOUBLE_EQ(e["dur"].get<double>(), 2.5);
    EXPECT_EQ(e["tid"], 1);
    EXPECT_EQ(e["args"]["frame"], 7);
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
