// Scheduler::build(): order derived from declarations, parallel passes, conflicts and cycles.
#include <gtest/gtest.h>

#include "engine/scheduler/scheduler.hpp"

namespace aloha {
namespace {

struct Transform {};
struct LodAttributes {};
struct LodRequest {};
struct Pose {};
struct CameraTag {};

SystemDesc Sys(std::string name, Phase phase, std::vector<ComponentTypeId> r, std::vector<ComponentTypeId> w) {
    return SystemDesc{std::move(name), phase, std::move(r), std::move(w), [](SystemContext&) {}};
}

using Names = std::vector<std::vector<std::string>>;

TEST(Plan, WriterRunsBeforeReaderWhateverTheRegistrationOrder) {
    Scheduler s(1);
    // The reader is added first; the writer must still come first.
    s.add(Sys("reader", Phase::Motion, reads<Transform>(), writes<Pose>()));
    s.add(Sys("writer", Phase::Motion, {}, writes<Transform>()));
    ASSERT_TRUE(s.build().ok());
    EXPECT_EQ(s.passes(), (Names{{"writer"}, {"reader"}}));
}

TEST(Plan, PhasesRunInOrderAndIndependentSystemsShareAPass) {
    Scheduler s(1);
    s.add(Sys("render", Phase::Render, reads<Pose>(), {}));
    s.add(Sys("rules", Phase::Rules, reads<LodAttributes>(), writes<LodRequest>()));
    s.add(Sys("attributes", Phase::Attributes, {reads<Transform>()[0], named_type_id("camera")},
              writes<LodAttributes>()));
    s.add(Sys("debug_a", Phase::Rules, reads<LodAttributes>(), {}));
    s.add(Sys("debug_b", Phase::Rules, reads<LodRequest>(), {}));
    ASSERT_TRUE(s.build().ok());
    // Rules: 'rules' and 'debug_a' only read LodAttributes -> one pass; 'debug_b' reads what
    // 'rules' writes -> next pass.
    EXPECT_EQ(s.passes(), (Names{{"attributes"}, {"rules", "debug_a"}, {"debug_b"}, {"render"}}));
    EXPECT_EQ(s.plan()[1].phase, Phase::Rules);
    const std::string d = s.describe();
    EXPECT_NE(d.find("phase Rules"), std::string::npos);
    EXPECT_NE(d.find("camera"), std::string::npos);
    EXPECT_NE(d.find("rules (reads:"), std::string::npos);
}

TEST(Plan, ChainsAcrossSeveralPassesAndResourceTags) {
    Scheduler s(1);
    s.add(Sys("c", Phase::Resolve, reads<LodRequest>(), {}));
    s.add(Sys("b", Phase::Resolve, reads<LodAttributes>(), writes<LodRequest>()));
    s.add(Sys("a", Phase::Resolve, {}, {resource_type_id<CameraTag>(), component_type_id<LodAttributes>()}));
    s.add(Sys("d", Phase::Resolve, {resource_type_id<CameraTag>()}, {}));
    ASSERT_TRUE(s.build().ok());
    EXPECT_EQ(s.passes(), (Names{{"a"}, {"b", "d"}, {"c"}}));
}

TEST(Plan, TwoWritersOfOneTypeAreRejectedNamingBothAndTheType) {
    Scheduler s(1);
    s.add(Sys("walker", Phase::Motion, {}, writes<Pose>()));
    s.add(Sys("ik", Phase::Motion, reads<Transform>(), writes<Pose>()));
    s.add(Sys("elsewhere", Phase::Skin, {}, writes<Pose>()));  // another phase: allowed
    const Status st = s.build();
    ASSERT_FALSE(st.ok());
    const std::string& m = st.error().message;
    EXPECT_NE(m.find("'walker'"), std::string::npos) << m;
    EXPECT_NE(m.find("'ik'"), std::string::npos) << m;
    EXPECT_NE(m.find("Pose"), std::string::npos) << m;
    EXPECT_NE(m.find("Motion"), std::string::npos) << m;
    EXPECT_EQ(m.find("elsewhere"), std::string::npos) << m;
    EXPECT_FALSE(s.built());
}

TEST(Plan, CyclesDuplicatesAndMissingBodiesAreAllListed) {
    Scheduler s(1);
    s.add(Sys("x", Phase::Skin, reads<Transform>(), writes<Pose>()));
    s.add(Sys("y", Phase::Skin, reads<Pose>(), writes<Transform>()));
    ASSERT_FALSE(s.build().ok());
    EXPECT_NE(s.build().error().message.find("cycle"), std::string::npos);

    Scheduler t(1);
    t.add(Sys("same", Phase::Skin, {}, {}));
    t.add(Sys("same", Phase::Render, {}, {}));
    t.add(SystemDesc{"nobody", Phase::Render, {}, {}, {}});
    const Status st = t.build();
    ASSERT_FALSE(st.ok());
    EXPECT_NE(st.error().message.find("two systems are named 'same'"), std::string::npos);
    EXPECT_NE(st.error().message.find("'nobody' has no run function"), std::string::npos);
}

TEST(Plan, AddingInvalidatesTheBuild) {
    Scheduler s(1);
    s.add(Sys("a", Phase::Render, {}, {}));
    ASSERT_TRUE(s.build().ok());
    s.add(Sys("b", Phase::Render, {}, {}));
    EXPECT_FALSE(s.built());
    ASSERT_TRUE(s.build().ok());
    EXPECT_EQ(s.passes(), (Names{{"a", "b"}}));
}

}  // namespace
}  // namespace aloha
