# LOD benchmarks: attributes, rule evaluation (10 rules over 100,000 characters), resolver.
aloha_bench(lod_bench SOURCES ${CMAKE_CURRENT_LIST_DIR}/lod_bench.cpp LIBS aloha::lod)
