# Inverse kinematics (CCD per eq. 9-11, damped least squares); included by systems/motion/CMakeLists.txt.
list(APPEND ALOHA_MOTION_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/joint_limits.cpp
  ${CMAKE_CURRENT_LIST_DIR}/chain_fk.cpp
  ${CMAKE_CURRENT_LIST_DIR}/ik_chain.cpp
  ${CMAKE_CURRENT_LIST_DIR}/ccd.cpp
  ${CMAKE_CURRENT_LIST_DIR}/dls.cpp
  ${CMAKE_CURRENT_LIST_DIR}/ik_hooks.cpp)
