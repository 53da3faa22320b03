# Geometric controller: per-character cost of GeometryController::update per method (humanoid).
aloha_bench(geomctl_bench SOURCES ${CMAKE_CURRENT_LIST_DIR}/geomctl_bench.cpp LIBS aloha::geometry aloha::assets)
