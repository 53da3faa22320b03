# ECS iteration: View vs Group spans vs a plain struct-of-arrays loop (the lower bound).
aloha_bench(ecs_bench SOURCES ${CMAKE_CURRENT_LIST_DIR}/ecs_bench.cpp LIBS aloha::ecs)
