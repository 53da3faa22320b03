# Dynamic walk benchmark: cost per character-step.
if(TARGET aloha_motion)
  aloha_bench(dynamic_bench SOURCES ${CMAKE_CURRENT_LIST_DIR}/dynamic_bench.cpp LIBS aloha::motion)
endif()
