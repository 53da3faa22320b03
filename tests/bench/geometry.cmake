# Geometry (muscle layer) benchmarks: muscle shape + tessellation per character at several (T, P).
aloha_bench(geometry_bench SOURCES ${CMAKE_CURRENT_LIST_DIR}/geometry_bench.cpp LIBS aloha::geometry)
