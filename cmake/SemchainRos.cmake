# Finds ROS 1 (roscpp, rosbag, tf2 and the message packages of DESIGN.md section 5.7) for the
# optional module src/ros. Sets SEMCHAIN_ROS_FOUND and, when found, the INTERFACE target
# semchain_ros_deps (alias semchain::ros_deps) with ROS's include directories as SYSTEM includes,
# so that warnings in ROS headers do not fail a -Werror build.
#
# ROS's CMake files are catkin's: they run Python (catkin_pkg for catkin, ament_package for
# pluginlib, which rosbag uses), and a Python without those modules is a hard configure error
# even with QUIET. So an interpreter that has them is chosen first: -DPython3_EXECUTABLE when
# given, else python3 on the PATH, else /usr/bin/python3 (Debian's, where the ROS packages put
# their modules). Everything runs inside a function so that catkin's variables (it turns
# BUILD_SHARED_LIBS on, for one) stay out of the project's scope.

include(SemchainRosCxx20)

set(SEMCHAIN_ROS_PACKAGES
    roscpp rosbag_storage tf2 tf2_ros std_msgs sensor_msgs nav_msgs geometry_msgs tf2_msgs
    visualization_msgs std_srvs)

function(_semchain_ros_python out)
  if(Python3_EXECUTABLE)
    set(candidates ${Python3_EXECUTABLE})
  else()
    find_program(_semchain_path_python NAMES python3 NO_CACHE)
    set(candidates ${_semchain_path_python} /usr/bin/python3)
  endif()
  foreach(python IN LISTS candidates)
    if(NOT EXISTS "${python}")
      continue()
    endif()
    execute_process(COMMAND ${python} -c "import catkin_pkg, ament_package"
                    RESULT_VARIABLE result OUTPUT_QUIET ERROR_QUIET)
    if(result EQUAL 0)
      set(${out} ${python} PARENT_SCOPE)
      return()
    endif()
  endforeach()
  set(${out} "" PARENT_SCOPE)
endfunction()

function(semchain_find_ros)
  set(SEMCHAIN_ROS_FOUND FALSE PARENT_SCOPE)
  _semchain_ros_python(python)
  if(NOT python)
    message(STATUS "ROS 1: not found (no Python with catkin_pkg and ament_package; install "
                   "the ROS packages of scripts/install_deps.sh or pass -DPython3_EXECUTABLE=) "
                   "- building without src/ros and 'semchain bag'")
    return()
  endif()
  set(Python3_EXECUTABLE ${python})
  set(PYTHON_EXECUTABLE ${python})
  set(CATKIN_ENABLE_TESTING OFF)
  # Without this catkin would install its workspace scripts (setup.bash, env.sh, _setup_util.py)
  # into the root of the install prefix (cmake/SemchainInstall.cmake says what is installed).
  set(CATKIN_INSTALL_INTO_PREFIX_ROOT FALSE)
  # catkin sets directory-wide definitions and caches BUILD_SHARED_LIBS ON; both are put back
  # afterwards, and the definitions ROS's headers want go onto semchain_ros_deps only.
  get_directory_property(definitions_before COMPILE_DEFINITIONS)
  if(NOT DEFINED CACHE{BUILD_SHARED_LIBS})
    set(unset_shared_libs TRUE)
  endif()
  find_package(catkin QUIET COMPONENTS ${SEMCHAIN_ROS_PACKAGES})
  get_directory_property(ros_definitions COMPILE_DEFINITIONS)
  set_directory_properties(PROPERTIES COMPILE_DEFINITIONS "${definitions_before}")
  if(definitions_before)
    list(REMOVE_ITEM ros_definitions ${definitions_before})
  endif()
  list(REMOVE_ITEM ros_definitions ROS_BUILD_SHARED_LIBS=1)
  if(unset_shared_libs)
    unset(BUILD_SHARED_LIBS CACHE)
  endif()
  set(missing "")
  foreach(package IN LISTS SEMCHAIN_ROS_PACKAGES)
    if(NOT ${package}_FOUND)
      list(APPEND missing ${package})
    endif()
  endforeach()
  if(NOT catkin_FOUND OR missing)
    if(NOT catkin_FOUND)
      set(missing catkin)
    endif()
    string(REPLACE ";" ", " missing "${missing}")
    message(STATUS "ROS 1: not found (missing ${missing}) - building without src/ros and "
                   "'semchain bag'")
    return()
  endif()
  find_path(_semchain_ros_root ros/serialization.h HINTS ${catkin_INCLUDE_DIRS} NO_CACHE)
  set(fixed ${CMAKE_BINARY_DIR}/ros_cxx20/include)
  foreach(root IN LISTS _semchain_ros_root catkin_INCLUDE_DIRS)
    semchain_ros_cxx20_headers(${root} ${fixed})
  endforeach()
  add_library(semchain_ros_deps INTERFACE)
  add_library(semchain::ros_deps ALIAS semchain_ros_deps)
  target_include_directories(semchain_ros_deps SYSTEM BEFORE INTERFACE ${fixed})
  target_include_directories(semchain_ros_deps SYSTEM INTERFACE ${catkin_INCLUDE_DIRS})
  target_link_libraries(semchain_ros_deps INTERFACE ${catkin_LIBRARIES})
  target_compile_definitions(semchain_ros_deps INTERFACE ${ros_definitions})
  message(STATUS "ROS 1: found (${python}) - building src/ros and 'semchain bag'")
  set(SEMCHAIN_ROS_FOUND TRUE PARENT_SCOPE)
endfunction()
