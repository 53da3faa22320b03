# IK tests (CCD, DLS, joint limits); included by tests/systems/motion/CMakeLists.txt.
aloha_test(ik_tests
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/ik_test.cpp
          ${CMAKE_CURRENT_LIST_DIR}/ik_limits_test.cpp
          ${CMAKE_CURRENT_LIST_DIR}/ik_hooks_test.cpp
  LIBS aloha::motion
  LABELS motion ik)
