// Significance as data: the expression language (precedence, functions, attributes), the default
// expression equal to the original fixed formula, and errors that name the file, line and column
// of the bad token inside the rule file's "significance" string.
#include "systems/lod/frame_budget.hpp"
#include "systems/lod/significance.hpp"
#include "tests/systems/lod/lod_test_util.hpp"

#include "engine/core/text_position.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace aloha {
namespace {

using lod_test::at_distance;
using lod_test::small_rules;

// Compiles `text` expecting success; fails the test otherwise.
SignificanceExpr must_compile(const std::string& text) {
    SignificanceExpr e;
    ExprError error;
    EXPECT_TRUE(e.compile(text, &error)) << text << ": " << error.message << " at " << error.offset;
    return e;
}

// Compiles `text` expecting failure; returns the error.
ExprError compile_error(const std::string& text) {
    SignificanceExpr e;
    ExprError error;
    EXPECT_FALSE(e.compile(text, &error)) << text;
    return error;
}

TEST(Significance, DefaultIsTheOriginalFormula) {
    // The original fixed formula, written out: projected_height_px * (0.25 + importance) / (1 + e^2), 0 off screen.
    auto original = [](const LodAttributes& a) {
        if (a.visible == 0) return 0.0f;
        const float e = std::min(a.eccentricity, 1.0e3f);
        return a.projected_height_px * (0.25f + a.importance) / (1.0f + e * e);
    };
    const SignificanceExpr def;
    EXPECT_EQ(def.text(), kDefaultSignificance);
    for (float d : {1.0f, 7.5f, 40.0f}) {
        for (float ecc : {0.0f, 0.6f, 1.3f, 1.0e6f}) {
            LodAttributes a = at_distance(d);
            a.eccentricity = ecc;
            a.importance = 0.3f;
            // Same operations in the same order, but pow(e, 2) against e * e: a few ulps apart at most.
            EXPECT_NEAR(def.evaluate(a), original(a), 1e-5f * original(a) + 1e-30f) << d << " " << ecc;
            EXPECT_FLOAT_EQ(noticeability(a), def.evaluate(a));
            a.visible = 0;
            EXPECT_EQ(def.evaluate(a), 0.0f);
        }
    }
}

TEST(Significance, PrecedenceFunctionsAndAttributes) {
    LodAttributes a;
    a.distance = 10.0f;
    a.projected_height_px = 200.0f;
    a.eccentricity = 0.5f;
    a.speed = 1.5f;
    a.importance = 0.25f;
    a.visible = 1;
    a.occluded = 0.75f;
    EXPECT_FLOAT_EQ(must_compile("1 + 2 * 3").evaluate(a), 7.0f);
    EXPECT_FLOAT_EQ(must_compile("(1 + 2) * 3").evaluate(a), 9.0f);
    EXPECT_FLOAT_EQ(must_compile("2 ^ 3 ^ 2").evaluate(a), 512.0f);  // right-associative: 2^(3^2)
    EXPECT_FLOAT_EQ(must_compile("-2 ^ 2").evaluate(a), -4.0f);      // power binds tighter than minus
    EXPECT_FLOAT_EQ(must_compile("10 - 4 - 3").evaluate(a), 3.0f);   // left-associative
    EXPECT_FLOAT_EQ(must_compile("distance / 4 / 5").evaluate(a), 0.5f);
    EXPECT_FLOAT_EQ(must_compile("min(distance, speed, 3)").evaluate(a), 1.5f);
    EXPECT_FLOAT_EQ(must_compile("max(importance, occluded)").evaluate(a), 0.75f);
    EXPECT_FLOAT_EQ(must_compile("abs(-speed) + sqrt(16)").evaluate(a), 5.5f);
    EXPECT_FLOAT_EQ(must_compile("clamp(projected_height_px, 0, 100)").evaluate(a), 100.0f);
    EXPECT_FLOAT_EQ(must_compile("visible * (1 - occluded) * eccentricity").evaluate(a), 0.125f);
    EXPECT_FLOAT_EQ(must_compile("  1.5e2  ").evaluate(a), 150.0f);
    // Never NaN: 0/0 becomes 0; x/0 the largest finite float.
    EXPECT_EQ(must_compile("0 / 0").evaluate(a), 0.0f);
    EXPECT_EQ(must_compile("1 / 0").evaluate(a), FLT_MAX);
}

TEST(Significance, ErrorsSayWhereAndWhat) {
    ExprError e = compile_error("distance + speeed");
    EXPECT_EQ(e.offset, 11u);
    EXPECT_NE(e.message.find("unknown name 'speeed'"), std::string::npos) << e.message;
    e = compile_error("min(distance)");
    EXPECT_EQ(e.offset, 0u);
    EXPECT_NE(e.message.find("2 or more"), std::string::npos) << e.message;
    e = compile_error("(distance + 1");
    EXPECT_EQ(e.offset, 13u);  // where the ')' is missing: the end
    e = compile_error("distance 2");
    EXPECT_EQ(e.offset, 9u);
    e = compile_error("distance * # 2");
    EXPECT_EQ(e.offset, 11u);
    e = compile_error("tier * 2");
    EXPECT_NE(e.message.find("not a per-character attribute"), std::string::npos) << e.message;
    e = compile_error("log(distance)");
    EXPECT_NE(e.message.find("unknown function 'log'"), std::string::npos) << e.message;
    e = compile_error("");
    EXPECT_NE(e.message.find("ends where a value is expected"), std::string::npos) << e.message;
    // Nesting deeper than the evaluation stack is refused, not overflowed.
    std::string deep;
    for (int i = 0; i < SignificanceExpr::kMaxStack + 1; ++i) deep += "1 + (";
    deep += "1";
    for (int i = 0; i < SignificanceExpr::kMaxStack + 1; ++i) deep += ")";
    e = compile_error(deep);
    EXPECT_NE(e.message.find("nests too deeply"), std::string::npos) << e.message;
}

TEST(Significance, RuleFileErrorNamesFileLineAndColumn) {
    // The expression sits on its own line of the file; the bad name is found by searching that line,
    // independently of the code under test.
    nlohmann::json j = small_rules();
    j["significance"] = "projected_height_px * (0.25 + importanse)";
    const std::string text = j.dump(2);
    const size_t at = text.find("importanse");
    ASSERT_NE(at, std::string::npos);
    int line = 1;
    size_t line_start = 0;
    for (size_t i = 0; i < at; ++i)
        if (text[i] == '\n') ++line, line_start = i + 1;
    std::vector<Error> errors;
    Result<RuleTable> r = parse_rules(text, "sig.json", &errors);
    ASSERT_FALSE(r.ok());
    ASSERT_EQ(errors.size(), 1u) << join_errors(errors);
    EXPECT_EQ(errors[0].file, "sig.json");
    EXPECT_EQ(errors[0].line, line);
    EXPECT_EQ(errors[0].column, static_cast<int>(at - line_start) + 1);
    EXPECT_EQ(errors[0].path, "/significance");
    EXPECT_NE(errors[0].message.find("unknown name 'importanse'"), std::string::npos) << errors[0].message;
    EXPECT_NE(errors[0].to_string().find("sig.json:" + std::to_string(line) + ":"), std::string::npos);
}

TEST(Significance, ColumnCountsRawBytesOfEscapes) {
    // \u0020 is one decoded space but six bytes in the file; \" two. The column must point at the file.
    const std::string text = R"({ "significance": "\"x\" \u0020 + 1",
  "x": 1 })";
    const size_t start = find_top_level_string(text, "significance");
    ASSERT_EQ(start, 19u);
    EXPECT_EQ(raw_offset_in_string(text, start, 0), 19u);  // decoded '"': the '\' of \"
    EXPECT_EQ(raw_offset_in_string(text, start, 1), 21u);  // x
    EXPECT_EQ(raw_offset_in_string(text, start, 4), 25u);  // the space of \u0020 starts at its '\'
    EXPECT_EQ(raw_offset_in_string(text, start, 5), 31u);  // the next byte follows its six bytes
    int line = 0, column = 0;
    line_column_of(text, 25, &line, &column);
    EXPECT_EQ(line, 1);
    EXPECT_EQ(column, 26);
    line_column_of(text, text.find("\"x\": 1"), &line, &column);
    EXPECT_EQ(line, 2);
    EXPECT_EQ(column, 3);
    // A key that only appears deeper, or as a value, is not a top-level member.
    EXPECT_EQ(find_top_level_string(R"({"a": {"significance": "x"}, "b": "significance"})", "significance"),
              std::string::npos);
    // Comments are skipped.
    EXPECT_EQ(find_top_level_string("{ // \"significance\": \"no\"\n \"significance\": \"yes\" }", "significance"),
              44u);

    // Through the rule loader: an escape before the bad name still gives the file's column.
    std::string file = small_rules().dump(2);
    file.insert(1, "\n  \"significance\": \"distance\\u0020+ speeed\",");
    std::vector<Error> errors;
    ASSERT_FALSE(parse_rules(file, "esc.json", &errors).ok());
    ASSERT_EQ(errors.size(), 1u) << join_errors(errors);
    EXPECT_EQ(errors[0].line, 2);
    EXPECT_EQ(errors[0].column, static_cast<int>(file.find("speeed") - file.find('\n')));
}

TEST(Significance, RuleFileExpressionIsUsed) {
    nlohmann::json j = small_rules();
    j["significance"] = "importance * 10 - distance";
    const RuleTable t = lod_test::must_parse(j);
    LodAttributes a = at_distance(4.0f);
    a.importance = 0.5f;
    EXPECT_FLOAT_EQ(t.significance.evaluate(a), 1.0f);
    EXPECT_EQ(t.significance.text(), "importance * 10 - distance");
    // Without the key: the default.
    const RuleTable d = lod_test::must_parse(small_rules());
    EXPECT_EQ(d.significance.text(), kDefaultSignificance);
}

}  // namespace
}  // namespace aloha
