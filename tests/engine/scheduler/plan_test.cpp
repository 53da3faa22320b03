// Scheduler::build(): order derived from declarations, parallel passes, conflicts and cycles.
#include <gtest/gtest.h>

#include "engine/scheduler/scheduler.hpp"
#include "tests/engine/scheduler/test_phases.hpp"

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
    Scheduler s(test::test_phases(), 1);
    // The reader is added first; the writer must still come first.
    s.add(Sys("reader", test::TestPhase::Motion, reads<Transform>(), writes<Pose>()));
    s.add(Sys("writer", test::TestPhase::Motion, {}, writes<Transform>()));
    ASSERT_TRUE(s.build().ok());
    EXPECT_EQ(s.passes(), (Names{{"writer"}, {"reader"}}));
}

TEST(Plan, PhasesRunInOrderAndIndependentSystemsShareAPass) {
    Scheduler s(test::test_phases(), 1);
    s.add(Sys("render", test::TestPhase::Render, reads<Pose>(), {}));
    s.add(Sys("rules", test::TestPhase::Rules, reads<LodAttributes>(), writes<LodRequest>()));
    s.add(Sys("attributes", test::TestPhase::Attributes, {reads<Transform>()[0], named_type_id("camera")},
              writes<LodAttributes>()));
    s.add(Sys("debug_a", test::TestPhase::Rules, reads<LodAttributes>(), {}));
    s.add(Sys("debug_b", test::TestPhase::Rules, reads<LodRequest>(), {}));
    ASSERT_TRUE(s.build().ok());
    // Rules: 'rules' and 'debug_a' only read LodAttributes -> one pass; 'debug_b' reads what
    // 'rules' writes -> next pass.
    EXPECT_EQ(s.passes(), (Names{{"attributes"}, {"rules", "debug_a"}, {"debug_b"}, {"render"}}));
    EXPECT_EQ(s.plan()[1].phase, test::TestPhase::Rules);
    const std::string d = s.describe();
    EXPECT_NE(d.find("phase Rules"), std::string::npos);
    EXPECT_NE(d.find("camera"), std::string::npos);
    EXPECT_NE(d.find("rules (reads:"), std::string::npos);
}

TEST(Plan, ChainsAcrossSeveralPassesAndResourceTags) {
    Scheduler s(test::test_phases(), 1);
    s.add(Sys("c", test::TestPhase::Resolve, reads<LodRequest>(), {}));
    s.add(Sys("b", test::TestPhase::Resolve, reads<LodAttributes>(), writes<LodRequest>()));
    s.add(Sys("a", test::TestPhase::Resolve, {}, {resource_type_id<CameraTag>(), component_type_id<LodAttributes>()}));
    s.add(Sys("d", test::TestPhase::Resolve, {resource_type_id<CameraTag>()}, {}));
    ASSERT_TRUE(s.build().ok());
    EXPECT_EQ(s.passes(), (Names{{"a"}, {"b", "d"}, {"c"}}));
}

TEST(Plan, TwoWritersOfOneTypeAreRejectedNamingBothAndTheType) {
    Scheduler s(test::test_phases(), 1);
    s.add(Sys("walker", test::TestPhase::Motion, {}, writes<Pose>()));
    s.add(Sys("ik", test::TestPhase::Motion, reads<Transform>(), writes<Pose>()));
    s.add(Sys("elsewhere", test::TestPhase::Skin, {}, writes<Pose>()));  // another phase: allowed
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
    Scheduler s(test::test_phases(), 1);
    s.add(Sys("x", test::TestPhase::Skin, reads<Transform>(), writes<Pose>()));
    s.add(Sys("y", test::TestPhase::Skin, reads<Pose>(), writes<Transform>()));
    ASSERT_FALSE(s.build().ok());
    EXPECT_NE(s.build().error().message.find("cycle"), std::string::npos);

    Scheduler t(test::test_phases(), 1);
    t.add(Sys("same", test::TestPhase::Skin, {}, {}));
    t.add(Sys("same", test::TestPhase::Render, {}, {}));
    t.add(SystemDesc{"nobody", test::TestPhase::Render, {}, {}, {}});
    const Status st = t.build();
    ASSERT_FALSE(st.ok());
    EXPECT_NE(st.error().message.find("two systems are named 'same'"), std::string::npos);
    EXPECT_NE(st.error().message.find("'nobody' has no run function"), std::string::npos);
}

TEST(Plan, AddingInvalidatesTheBuild) {
    Scheduler s(test::test_phases(), 1);
    s.add(Sys("a", test::TestPhase::Render, {}, {}));
    ASSERT_TRUE(s.build().ok());
    s.add(Sys("b", test::TestPhase::Render, {}, {}));
    EXPECT_FALSE(s.built());
    ASSERT_TRUE(s.build().ok());
    EXPECT_EQ(s.passes(), (Names{{"a", "b"}}));
}

TEST(Plan, PhasesAreTheHostsData) {
    // A host with its own two phases: systems run in the host's order whatever order they were added in.
    Scheduler s({"physics", "draw"}, 1);
    s.add(Sys("draw_all", Phase{1}, reads<Pose>(), {}));
    s.add(Sys("step", Phase{0}, {}, writes<Pose>()));
    ASSERT_TRUE(s.build().ok());
    EXPECT_EQ(s.passes(), (Names{{"step"}, {"draw_all"}}));
    EXPECT_NE(s.describe().find("phase physics"), std::string::npos);
    EXPECT_EQ(s.phases(), (PhaseList{"physics", "draw"}));

    Scheduler outside({"only"}, 1);  // a system naming a phase the host does not declare
    outside.add(Sys("late", Phase{2}, {}, {}));
    const Status st = outside.build();
    ASSERT_FALSE(st.ok());
    EXPECT_NE(st.error().message.find("'late' has phase 2 but the host declares 1"), std::string::npos);

    EXPECT_FALSE(Scheduler(PhaseList{}, 1).build().ok());                  // no phases
    Scheduler twice({"a", "a"}, 1);
    EXPECT_NE(twice.build().error().message.find("unique and non-empty ('a')"), std::string::npos);
}

}  // namespace
}  // namespace aloha
