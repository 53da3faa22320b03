// The main() of every test program: points $ALOHA_DATA_DIR at the source tree's data/ (unless the caller
// set it) so "builtin:" names resolve as they do for the build-tree tool, then runs GoogleTest.
#include <gtest/gtest.h>

#include <cstdlib>

int main(int argc, char** argv) {
    setenv("ALOHA_DATA_DIR", ALOHA_SOURCE_DIR "/data", /*overwrite=*/0);
    testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
