# The machine's own stalls of a thread doing fixed work (not a Google Benchmark program: one long loop).
add_executable(bench_machine_stalls ${CMAKE_CURRENT_LIST_DIR}/machine_stalls.cpp)
aloha_warnings(bench_machine_stalls)
