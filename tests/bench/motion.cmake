# Motion benchmarks: clip sampling + local-to-model (ozz-animation comparison) and the controller.
if(TARGET aloha_motion)
  aloha_bench(motion_bench SOURCES ${CMAKE_CURRENT_LIST_DIR}/motion_bench.cpp LIBS aloha::motion)
endif()
