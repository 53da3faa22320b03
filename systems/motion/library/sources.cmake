# Generated motion library: gait relations, posing helpers, gait / idle / turn / wave clips.
list(APPEND ALOHA_MOTION_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/gait_model.cpp
  ${CMAKE_CURRENT_LIST_DIR}/pose_builder.cpp
  ${CMAKE_CURRENT_LIST_DIR}/posing.cpp
  ${CMAKE_CURRENT_LIST_DIR}/gait_clip.cpp
  ${CMAKE_CURRENT_LIST_DIR}/idle_clips.cpp
  ${CMAKE_CURRENT_LIST_DIR}/motion_library.cpp
  ${CMAKE_CURRENT_LIST_DIR}/loop_cut.cpp
  ${CMAKE_CURRENT_LIST_DIR}/loop_seam.cpp
  ${CMAKE_CURRENT_LIST_DIR}/foot_root_motion.cpp
  ${CMAKE_CURRENT_LIST_DIR}/retarget.cpp)
