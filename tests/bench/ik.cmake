# IK benchmark: time per CCD / DLS solve, writes error-vs-iteration curves (ik_convergence.csv).
if(TARGET aloha_motion)
  aloha_bench(ik_bench SOURCES ${CMAKE_CURRENT_LIST_DIR}/ik_bench.cpp LIBS aloha::motion)
endif()
