// The main() of every test program: points $ALOHA_DATA_DIR at the source tree's data/ (unless the caller
// set it) so "builtin:" names resolve as they do for the build-tree tool, and $ALOHA_CACHE_DIR at the
// build tree's bake_cache/ (unless set; made on first use) so the suite's processes, and the aloha tool
// they run, share one bake cache and leave the user's alone; then runs GoogleTest.
#include <gtest/gtest.h>

#include <cstdlib>

int main(int argc, char** argv) {
    setenv("ALOHA_DATA_DIR", ALOHA_SOURCE_DIR "/data", /*overwrite=*/0);
    setenv("ALOHA_CACHE_DIR", ALOHA_TEST_CACHE_DIR, /*overwrite=*/0);
    testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
