# Load-time surface work: closest-point maps between resolutions, the simplifier's distance bound.
aloha_bench(surface_bench SOURCES ${CMAKE_CURRENT_LIST_DIR}/surface_bench.cpp LIBS aloha::geometry)
