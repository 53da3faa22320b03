# Render benchmarks (lavapipe unless ALOHA_DEVICE says otherwise).
aloha_bench(render_bench SOURCES ${CMAKE_CURRENT_LIST_DIR}/render_bench.cpp LIBS aloha::render)
