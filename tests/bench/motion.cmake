# Motion benchmarks: clip sampling + local-to-model (ozz-animation comparison) and the controller.
if(TARGET aloha_motion)
  aloha_bench(motion_bench SOURCES ${CMAKE_CURRENT_LIST_DIR}/motion_bench.cpp LIBS aloha::motion)
endif()
# Controller on a 10,000-character crowd (serial vs parallel, throttling spread) and reach hooks.
if(TARGET aloha_motion)
  aloha_bench(motion_crowd_bench SOURCES ${CMAKE_CURRENT_LIST_DIR}/motion_crowd_bench.cpp LIBS aloha::motion)
endif()
