# The generated motion library (gait, idle, turn, wave) on the project's humanoid.
if(TARGET aloha_motion AND TARGET aloha_assets)
  aloha_test(motion_library_tests
    SOURCES
      ${CMAKE_CURRENT_LIST_DIR}/gait_clip_test.cpp
      ${CMAKE_CURRENT_LIST_DIR}/idle_clips_test.cpp
      ${CMAKE_CURRENT_LIST_DIR}/library_walk_test.cpp
      ${CMAKE_CURRENT_LIST_DIR}/loop_cut_test.cpp
      ${CMAKE_CURRENT_LIST_DIR}/loop_seam_test.cpp
      ${CMAKE_CURRENT_LIST_DIR}/foot_root_motion_test.cpp
      ${CMAKE_CURRENT_LIST_DIR}/retarget_test.cpp
    LIBS aloha::motion aloha::assets
    LABELS motion)
endif()
