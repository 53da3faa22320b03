#include "engine/core/result.hpp"
#include "engine/core/hash.hpp"

#include <gtest/gtest.h>

namespace aloha {
namespace {

TEST(Result, HoldsValueOrError) {
    Result<int> good = 4;
    ASSERT_TRUE(good.ok());
    EXPECT_EQ(good.value(), 4);
    Result<int> bad = make_error("scene.json", "expected a number", 3, 7, "/camera/fov");
    ASSERT_FALSE(bad.ok());
    EXPECT_EQ(bad.error().to_string(), "scene.json:3:7: /camera/fov: expected a number");
}

TEST(Result, StatusDefaultsToSuccess) {
    Status s;
    EXPECT_TRUE(s.ok());
    Status f = make_error("", "device lost");
    EXPECT_FALSE(f.ok());
    EXPECT_EQ(f.error().to_string(), "device lost");
}

TEST(Error, KindsLetCallersBranch) {
    EXPECT_EQ(make_error("a.json", "bad").kind, ErrorKind::Input);
    const Error io = make_error(ErrorKind::Io, "a.json", "file not found", 2);
    EXPECT_EQ(io.kind, ErrorKind::Io);
    EXPECT_EQ(io.to_string(), "a.json: file not found (code 2)");
    const Error option = option_error("s.json", "characters", "5 characters: no crowd");
    EXPECT_EQ(option.kind, ErrorKind::Option);
    EXPECT_EQ(option.path, "characters");  // the field, for the host to name its own flag or menu
    EXPECT_EQ(option.to_string(), "s.json: characters: 5 characters: no crowd");
}

TEST(StateHasher, SameBytesSameHashDifferentBytesDifferentHash) {
    StateHasher a, b, c;
    a.add(1.5f);
    b.add(1.5f);
    c.add(1.5000001f);
    EXPECT_EQ(a.value(), b.value());
    EXPECT_NE(a.value(), c.value());
}

}  // namespace
}  // namespace aloha
