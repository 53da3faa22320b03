# Fat springs + skin per character, OpenSubdiv level-1 evaluation, linear-blend skinning.
aloha_bench(skin_bench SOURCES ${CMAKE_CURRENT_LIST_DIR}/skin_bench.cpp LIBS aloha::geometry)
