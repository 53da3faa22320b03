# Scheduler overhead: empty systems per frame, parallel_for dispatch.
aloha_bench(scheduler_bench SOURCES ${CMAKE_CURRENT_LIST_DIR}/scheduler_bench.cpp LIBS aloha::scheduler)
